// Between the DDS threads and the matching thread: IMU samples queue up (the pipeline needs them
// all, in order); scans do not. A new scan replaces one still waiting, which is counted as
// skipped, so a matcher that falls behind works on the freshest scan and memory stays bounded.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>

#include <msg/LaserScan.h>

#include "core/Types.hpp"

namespace uavslam::matcher {

struct ReceivedScan {
  msg::LaserScan message;
  double published_at = 0.0;  // s, the writer's clock (DDS source timestamp)
};

class ScanQueue {
 public:
  // max_imu: a bound on waiting IMU samples (the oldest go first) should the matcher stall.
  explicit ScanQueue(std::size_t max_imu = 2000);

  void push_scan(ReceivedScan scan);
  void push_imu(const ImuSample& sample);

  // Waits up to `timeout` for a scan; returns it with every IMU sample received so far.
  // `imu_grace`: after a scan arrives, how long to wait for an IMU sample stamped at or after it,
  // so its orientation is interpolated rather than held.
  struct Work {
    ReceivedScan scan;
    std::deque<ImuSample> imu;
  };
  std::optional<Work> wait_for_scan(std::chrono::milliseconds timeout,
                                    std::chrono::milliseconds imu_grace);

  std::uint64_t scans_received() const;
  std::uint64_t scans_skipped() const;
  std::uint64_t imu_dropped() const;

 private:
  double scan_stamp_locked() const;

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<ReceivedScan> scan_;
  std::deque<ImuSample> imu_;
  std::size_t max_imu_;
  double newest_imu_stamp_ = -1e300;
  std::uint64_t scans_received_ = 0;
  std::uint64_t scans_skipped_ = 0;
  std::uint64_t imu_dropped_ = 0;
};

}  // namespace uavslam::matcher
