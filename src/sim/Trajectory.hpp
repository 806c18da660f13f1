// A smooth flight through timed waypoints: position and yaw are clamped cubic splines (zero
// velocity at both ends); a multirotor's roll and pitch follow from the acceleration, as its thrust
// must point along acceleration + gravity; a ground robot stays level.
#pragma once

#include <vector>

#include "core/Types.hpp"
#include "sim/CubicSpline.hpp"
#include "sim/Scenario.hpp"

namespace uavslam::sim {

constexpr double kGravity = 9.80665;  // m/s^2

class Trajectory {
 public:
  // Throws std::invalid_argument if fewer than 2 waypoints or times not strictly increasing.
  explicit Trajectory(std::vector<Waypoint> waypoints, Vehicle vehicle = Vehicle::multirotor);

  double start_time() const { return waypoints_.front().t; }
  double end_time() const { return waypoints_.back().t; }
  const std::vector<Waypoint>& waypoints() const { return waypoints_; }

  // All of these clamp t to [start_time, end_time]. Velocity and acceleration are in the world
  // frame, the angular velocity in the body frame.
  Pose pose_at(double t) const;
  Vec3 velocity_at(double t) const;
  Vec3 acceleration_at(double t) const;
  Vec3 angular_velocity_at(double t) const;
  double yaw_at(double t) const;  // rad, unwrapped (continuous over the flight)

 private:
  Eigen::Quaterniond orientation_at(double t) const;
  double clamp_time(double t) const;

  std::vector<Waypoint> waypoints_;
  Vehicle vehicle_;
  std::vector<CubicSpline> position_splines_;  // x, y, z
  CubicSpline yaw_spline_;
};

}  // namespace uavslam::sim
