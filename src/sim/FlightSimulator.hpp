// A whole simulated flight: the world, the trajectory and the sensors, read as independent,
// deterministic, time-ordered streams (LiDAR scans, IMU samples and, when the scenario has a
// velocity source, velocity samples). Separate
// processes each owning a FlightSimulator of the same scenario see exactly the same data.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "core/Types.hpp"
#include "sim/ImuSimulator.hpp"
#include "sim/LidarSimulator.hpp"
#include "sim/SampleClock.hpp"
#include "sim/Scenario.hpp"
#include "sim/Trajectory.hpp"
#include "sim/VelocitySimulator.hpp"
#include "sim/World.hpp"

namespace uavslam::sim {

class FlightSimulator {
 public:
  explicit FlightSimulator(const Scenario& scenario);

  // Movable (the world lives on the heap, where the LiDAR points to it), not copyable.
  FlightSimulator(FlightSimulator&&) = default;
  FlightSimulator& operator=(FlightSimulator&&) = default;
  FlightSimulator(const FlightSimulator&) = delete;
  FlightSimulator& operator=(const FlightSimulator&) = delete;

  // The next scan (stamps start, start + 1/rate_hz, ... up to end; sequence 0, 1, ...);
  // false when the flight is over. A late scan (faults.late_scan_every) sees the world from
  // where the body was faults.late_scan_s before its stamp.
  bool next_scan(Scan& out);
  // The next IMU sample (stamps start, start + 1/imu rate, ...); false when the flight is over.
  bool next_imu(ImuSample& out);
  // The next velocity sample (stamps start, start + 1/velocity rate, ...); false when the flight
  // is over or the scenario has no velocity source.
  bool next_velocity(VelocitySample& out);

  Pose ground_truth_at(double t) const { return trajectory_.pose_at(t); }
  const World& world() const { return *world_; }
  const Trajectory& trajectory() const { return trajectory_; }
  std::shared_ptr<const ScanGeometry> scan_geometry() const { return lidar_.geometry(); }
  double start_time() const { return trajectory_.start_time(); }
  double end_time() const { return trajectory_.end_time(); }

 private:
  std::unique_ptr<const World> world_;
  Trajectory trajectory_;
  LidarSimulator lidar_;
  ImuSimulator imu_;
  SampleClock scan_clock_;
  SampleClock imu_clock_;
  VelocitySimulator velocity_;
  FaultSpec faults_;
  std::optional<SampleClock> velocity_clock_;  // none without a velocity source
  std::uint64_t next_scan_index_ = 0;
  std::uint64_t next_imu_index_ = 0;
  std::uint64_t next_velocity_index_ = 0;
};

}  // namespace uavslam::sim
