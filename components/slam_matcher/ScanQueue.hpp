// Between the DDS threads and the matching thread: IMU, odometry and velocity samples queue up (the
// pipeline needs them all, in order); scans queue up only within a backlog: a waiting scan older
// than the newest by more than max_backlog_s (sensor time) is dropped and counted as skipped. So
// scans that arrive in a burst (a RELIABLE reader delivers in order, and a fragment resent over a
// lossy link holds back the scans behind it) are all matched, while a matcher that falls behind
// works on fresh scans and memory stays bounded. A backlog of 0 keeps only the newest scan.
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
  // max_samples: a bound on waiting IMU samples, and on waiting odometry samples (the oldest go
  // first) should the matcher stall. wait_for_odometry: the matcher uses the odometry, so the
  // grace of wait_for_scan waits for it too.
  // max_backlog_s: how far (sensor time) the oldest waiting scan may lag the newest.
  explicit ScanQueue(bool wait_for_odometry = false, double max_backlog_s = kDefaultBacklog,
                     std::size_t max_samples = 2000);

  static constexpr double kDefaultBacklog = 0.25;  // s: 10 scans at 40 Hz

  void push_scan(ReceivedScan scan);
  void push_imu(const ImuSample& sample);
  void push_odometry(const OdometrySample& sample);
  // Not waited for: a velocity that comes late is one the IMU prior does without.
  void push_velocity(const VelocitySample& sample);

  // Waits up to `timeout` for a scan; returns the oldest waiting one with every IMU and odometry
  // sample received so far. `grace`: after a scan arrives, how long to wait for an IMU sample (and,
  // when waited for, an odometry sample) stamped at or after it, so its orientation and odometry
  // position are interpolated rather than missing.
  struct Work {
    ReceivedScan scan;
    std::deque<ImuSample> imu;
    std::deque<OdometrySample> odometry;
    std::deque<VelocitySample> velocity;
  };
  std::optional<Work> wait_for_scan(std::chrono::milliseconds timeout,
                                    std::chrono::milliseconds grace);

  std::uint64_t scans_received() const;
  std::uint64_t scans_skipped() const;
  std::uint64_t imu_dropped() const;
  std::uint64_t odometry_received() const;
  std::uint64_t velocity_received() const;

 private:
  static double stamp_of(const ReceivedScan& scan);
  void drop_stale_scans_locked();

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<ReceivedScan> scans_;
  double max_backlog_s_;
  std::deque<ImuSample> imu_;
  std::deque<OdometrySample> odometry_;
  std::deque<VelocitySample> velocity_;
  bool wait_for_odometry_;
  std::size_t max_samples_;
  double newest_imu_stamp_ = -1e300;
  double newest_odometry_stamp_ = -1e300;
  std::uint64_t scans_received_ = 0;
  std::uint64_t scans_skipped_ = 0;
  std::uint64_t imu_dropped_ = 0;
  std::uint64_t odometry_received_ = 0;
  std::uint64_t velocity_received_ = 0;
};

}  // namespace uavslam::matcher
