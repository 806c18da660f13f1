// A simulated velocity source: the autopilot's estimate from optical flow or visual-inertial
// odometry, the true velocity in the IMU's drifting heading frame plus white noise.
#pragma once

#include <cstdint>
#include <random>

#include "core/Types.hpp"
#include "sim/Scenario.hpp"
#include "sim/Trajectory.hpp"

namespace uavslam::sim {

class VelocitySimulator {
 public:
  // imu: the attitude source whose heading frame the velocities are reported in.
  VelocitySimulator(const VelocitySpec& spec, const ImuSpec& imu, std::uint64_t seed);

  // The sample at time t of the flight. Draws 3 standard normals per call.
  VelocitySample sample_at(const Trajectory& trajectory, double t);

 private:
  VelocitySpec spec_;
  ImuSpec imu_;
  std::mt19937_64 random_;
  std::normal_distribution<double> standard_normal_{0.0, 1.0};
};

}  // namespace uavslam::sim
