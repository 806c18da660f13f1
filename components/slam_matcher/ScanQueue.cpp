#include "ScanQueue.hpp"

#include "dds/Conversions.hpp"

namespace uavslam::matcher {

ScanQueue::ScanQueue(bool wait_for_odometry, std::size_t max_samples)
    : wait_for_odometry_(wait_for_odometry), max_samples_(max_samples) {}

void ScanQueue::push_scan(ReceivedScan scan) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++scans_received_;
    if (scan_) ++scans_skipped_;
    scan_ = std::move(scan);
  }
  changed_.notify_all();
}

void ScanQueue::push_imu(const ImuSample& sample) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    imu_.push_back(sample);
    newest_imu_stamp_ = std::max(newest_imu_stamp_, sample.stamp);
    if (imu_.size() > max_samples_) {
      imu_.pop_front();
      ++imu_dropped_;
    }
  }
  changed_.notify_all();
}

void ScanQueue::push_odometry(const OdometrySample& sample) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++odometry_received_;
    odometry_.push_back(sample);
    newest_odometry_stamp_ = std::max(newest_odometry_stamp_, sample.stamp);
    if (odometry_.size() > max_samples_) odometry_.pop_front();
  }
  changed_.notify_all();
}

double ScanQueue::scan_stamp_locked() const {
  return dds::from_msg_time(scan_->message.header().stamp());
}

std::optional<ScanQueue::Work> ScanQueue::wait_for_scan(std::chrono::milliseconds timeout,
                                                        std::chrono::milliseconds grace) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!changed_.wait_for(lock, timeout, [&] { return scan_.has_value(); })) return std::nullopt;
  changed_.wait_for(lock, grace, [&] {
    const double stamp = scan_stamp_locked();
    return newest_imu_stamp_ >= stamp && (!wait_for_odometry_ || newest_odometry_stamp_ >= stamp);
  });
  Work work{std::move(*scan_), std::move(imu_), std::move(odometry_)};
  scan_.reset();
  imu_.clear();
  odometry_.clear();
  return work;
}

std::uint64_t ScanQueue::scans_received() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return scans_received_;
}

std::uint64_t ScanQueue::scans_skipped() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return scans_skipped_;
}

std::uint64_t ScanQueue::odometry_received() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return odometry_received_;
}

std::uint64_t ScanQueue::imu_dropped() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return imu_dropped_;
}

}  // namespace uavslam::matcher
