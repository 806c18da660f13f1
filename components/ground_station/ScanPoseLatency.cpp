#include "ScanPoseLatency.hpp"

namespace uavslam::ground_station {

ScanPoseLatency::ScanPoseLatency(std::size_t capacity) : scans_(capacity), poses_(capacity) {}

std::optional<double> ScanPoseLatency::add_scan(std::uint64_t scan_seq, double published_at) {
  if (const auto received_at = poses_.take(scan_seq)) return (*received_at - published_at) * 1e3;
  scans_.put(scan_seq, published_at);
  return std::nullopt;
}

std::optional<double> ScanPoseLatency::add_pose(std::uint64_t scan_seq, double received_at) {
  if (const auto published_at = scans_.take(scan_seq)) return (received_at - *published_at) * 1e3;
  poses_.put(scan_seq, received_at);
  return std::nullopt;
}

void ScanPoseLatency::Window::put(std::uint64_t seq, double time) {
  const std::uint64_t arrival = arrivals_++;
  entries_[seq] = {time, arrival};
  order_.emplace_back(seq, arrival);
  while (entries_.size() > capacity_ || order_.size() > 2 * capacity_) {
    const auto [old_seq, old_arrival] = order_.front();
    order_.pop_front();
    // A seq put again later, or already taken, has no entry of this arrival any more.
    const auto it = entries_.find(old_seq);
    if (it != entries_.end() && it->second.arrival == old_arrival) entries_.erase(it);
  }
}

std::optional<double> ScanPoseLatency::Window::take(std::uint64_t seq) {
  const auto it = entries_.find(seq);
  if (it == entries_.end()) return std::nullopt;
  const double time = it->second.time;
  entries_.erase(it);
  return time;
}

}  // namespace uavslam::ground_station
