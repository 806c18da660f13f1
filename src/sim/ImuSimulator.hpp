// A simulated IMU / autopilot attitude source: the true orientation with heading drift and
// attitude noise, plus noisy gyro rates and specific force.
#pragma once

#include <cstdint>
#include <random>

#include "core/Types.hpp"
#include "sim/Scenario.hpp"
#include "sim/Trajectory.hpp"

namespace uavslam::sim {

// The heading drift of the autopilot's attitude at time t of the flight (imu.yaw_drift): a turn
// about the world vertical that every quantity it reports in its own frame shares.
Eigen::Quaterniond heading_drift_at(const ImuSpec& spec, const Trajectory& trajectory, double t);

class ImuSimulator {
 public:
  ImuSimulator(const ImuSpec& spec, std::uint64_t seed);

  // The sample at time t of the flight. Draws 9 standard normals per call, whatever the spec's
  // noise levels, so the stream's randomness does not depend on them.
  ImuSample sample_at(const Trajectory& trajectory, double t);

 private:
  ImuSpec spec_;
  std::mt19937_64 random_;
  std::normal_distribution<double> standard_normal_{0.0, 1.0};
};

}  // namespace uavslam::sim
