// End-to-end latency scan -> pose: a pose names the scan it came from (scan_seq); its latency is
// when the pose arrived here minus when the scan was published (the scan writer's DDS source
// timestamp). Either may arrive first, so both sides wait, bounded, for their partner.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <unordered_map>

namespace uavslam::ground_station {

class ScanPoseLatency {
 public:
  // Keeps at most `capacity` unmatched scans and as many unmatched poses; the oldest go first.
  explicit ScanPoseLatency(std::size_t capacity = 1000);

  // Times in seconds on one clock (system clock since the epoch). Each returns the latency in ms
  // when its partner was already waiting.
  std::optional<double> add_scan(std::uint64_t scan_seq, double published_at);
  std::optional<double> add_pose(std::uint64_t scan_seq, double received_at);

 private:
  // Insertion-ordered and bounded: a restarted driver reuses low sequence numbers, so eviction
  // goes by arrival, not by number.
  class Window {
   public:
    explicit Window(std::size_t capacity) : capacity_(capacity) {}
    void put(std::uint64_t seq, double time);
    std::optional<double> take(std::uint64_t seq);

   private:
    struct Entry {
      double time;
      std::uint64_t arrival;
    };
    std::size_t capacity_;
    std::uint64_t arrivals_ = 0;
    std::unordered_map<std::uint64_t, Entry> entries_;
    std::deque<std::pair<std::uint64_t, std::uint64_t>> order_;  // (seq, arrival)
  };

  Window scans_;
  Window poses_;
};

}  // namespace uavslam::ground_station
