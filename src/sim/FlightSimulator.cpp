#include "sim/FlightSimulator.hpp"

namespace uavslam::sim {

FlightSimulator::FlightSimulator(const Scenario& scenario)
    : world_(std::make_unique<const World>(scenario.world)),
      trajectory_(scenario.waypoints, scenario.vehicle),
      lidar_(scenario.lidar, *world_, scenario.seed),
      imu_(scenario.imu, scenario.seed),
      scan_clock_(trajectory_.start_time(), trajectory_.end_time(), scenario.lidar.rate_hz),
      imu_clock_(trajectory_.start_time(), trajectory_.end_time(), scenario.imu.rate_hz),
      velocity_(scenario.velocity, scenario.imu, scenario.seed),
      faults_(scenario.faults) {
  if (scenario.velocity.rate_hz > 0.0) {
    velocity_clock_.emplace(trajectory_.start_time(), trajectory_.end_time(),
                            scenario.velocity.rate_hz);
  }
}

bool FlightSimulator::next_scan(Scan& out) {
  if (next_scan_index_ >= scan_clock_.count()) return false;
  const double stamp = scan_clock_.stamp(next_scan_index_);
  const int every = faults_.late_scan_every;
  const bool late =
      every > 0 && next_scan_index_ % std::uint64_t(every) == std::uint64_t(every) - 1;
  const double taken = late ? stamp - faults_.late_scan_s : stamp;
  out = lidar_.scan_along(trajectory_, taken, stamp, next_scan_index_);
  ++next_scan_index_;
  return true;
}

bool FlightSimulator::next_imu(ImuSample& out) {
  if (next_imu_index_ >= imu_clock_.count()) return false;
  out = imu_.sample_at(trajectory_, imu_clock_.stamp(next_imu_index_));
  ++next_imu_index_;
  return true;
}

bool FlightSimulator::next_velocity(VelocitySample& out) {
  if (!velocity_clock_ || next_velocity_index_ >= velocity_clock_->count()) return false;
  out = velocity_.sample_at(trajectory_, velocity_clock_->stamp(next_velocity_index_));
  ++next_velocity_index_;
  return true;
}

}  // namespace uavslam::sim
