#include "ScanQueue.hpp"

#include <cmath>

#include "dds/Conversions.hpp"

namespace uavslam::matcher {

ScanQueue::ScanQueue(bool wait_for_odometry, double max_backlog_s, std::size_t max_samples)
    : max_backlog_s_(max_backlog_s),
      wait_for_odometry_(wait_for_odometry),
      max_samples_(max_samples) {}

void ScanQueue::push_scan(ReceivedScan scan) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++scans_received_;
    scans_.push_back(std::move(scan));
    drop_stale_scans_locked();
  }
  changed_.notify_all();
}

// A scan stamped far behind the newest (or a restarted driver's scan far ahead of the old ones)
// is stale; the count bound holds even for scans that all carry one stamp.
void ScanQueue::drop_stale_scans_locked() {
  const double newest = stamp_of(scans_.back());
  const std::size_t max_scans = max_samples_;
  while (scans_.size() > 1 && (std::abs(newest - stamp_of(scans_.front())) > max_backlog_s_ ||
                               scans_.size() > max_scans)) {
    scans_.pop_front();
    ++scans_skipped_;
  }
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

void ScanQueue::push_velocity(const VelocitySample& sample) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++velocity_received_;
    velocity_.push_back(sample);
    if (velocity_.size() > max_samples_) velocity_.pop_front();
  }
  changed_.notify_all();
}

double ScanQueue::stamp_of(const ReceivedScan& scan) {
  return dds::from_msg_time(scan.message.header().stamp());
}

std::optional<ScanQueue::Work> ScanQueue::wait_for_scan(std::chrono::milliseconds timeout,
                                                        std::chrono::milliseconds grace) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!changed_.wait_for(lock, timeout, [&] { return !scans_.empty(); })) return std::nullopt;
  changed_.wait_for(lock, grace, [&] {
    const double stamp = stamp_of(scans_.front());
    return newest_imu_stamp_ >= stamp && (!wait_for_odometry_ || newest_odometry_stamp_ >= stamp);
  });
  Work work{std::move(scans_.front()), std::move(imu_), std::move(odometry_), std::move(velocity_)};
  scans_.pop_front();
  imu_.clear();
  odometry_.clear();
  velocity_.clear();
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

std::uint64_t ScanQueue::velocity_received() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return velocity_received_;
}

std::uint64_t ScanQueue::imu_dropped() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return imu_dropped_;
}

}  // namespace uavslam::matcher
