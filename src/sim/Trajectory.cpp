#include "sim/Trajectory.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "core/Angles.hpp"

namespace uavslam::sim {

namespace {

std::vector<Waypoint> validated(std::vector<Waypoint> waypoints) {
  if (waypoints.size() < 2) {
    std::ostringstream message;
    message << "Trajectory: needs at least 2 waypoints, got " << waypoints.size();
    throw std::invalid_argument(message.str());
  }
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    if (!(waypoints[i].t > waypoints[i - 1].t)) {
      std::ostringstream message;
      message << "Trajectory: waypoint times must be strictly increasing, but waypoint " << i
              << " has t = " << waypoints[i].t << " after t = " << waypoints[i - 1].t;
      throw std::invalid_argument(message.str());
    }
  }
  return waypoints;
}

std::vector<double> waypoint_times(const std::vector<Waypoint>& waypoints) {
  std::vector<double> times;
  for (const Waypoint& w : waypoints) times.push_back(w.t);
  return times;
}

// Zero end velocities: the UAV hovers at the first and the last waypoint.
CubicSpline resting_spline(const std::vector<Waypoint>& waypoints, std::vector<double> values) {
  return CubicSpline(waypoint_times(waypoints), std::move(values), 0.0, 0.0);
}

std::vector<CubicSpline> make_position_splines(const std::vector<Waypoint>& waypoints) {
  std::vector<CubicSpline> splines;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> values;
    for (const Waypoint& w : waypoints) values.push_back(w.position[axis]);
    splines.push_back(resting_spline(waypoints, std::move(values)));
  }
  return splines;
}

// Each yaw takes the shortest turn from the one before, so 170 -> -170 degrees is a 20 degree turn.
CubicSpline make_yaw_spline(const std::vector<Waypoint>& waypoints) {
  std::vector<double> unwrapped{deg_to_rad(waypoints.front().yaw_deg)};
  for (std::size_t i = 1; i < waypoints.size(); ++i) {
    const double turn = wrap_angle(deg_to_rad(waypoints[i].yaw_deg) - unwrapped.back());
    unwrapped.push_back(unwrapped.back() + turn);
  }
  return resting_spline(waypoints, std::move(unwrapped));
}

// Body z along the thrust, body x as close to the heading as that allows.
Eigen::Quaterniond multirotor_orientation(const Vec3& acceleration, double yaw) {
  const Vec3 z_body = (acceleration + kGravity * Vec3::UnitZ()).normalized();
  const Vec3 x_heading(std::cos(yaw), std::sin(yaw), 0.0);
  const Vec3 y_body = z_body.cross(x_heading).normalized();
  const Vec3 x_body = y_body.cross(z_body);
  Eigen::Matrix3d rotation;
  rotation << x_body, y_body, z_body;
  return Eigen::Quaterniond(rotation).normalized();
}

}  // namespace

Trajectory::Trajectory(std::vector<Waypoint> waypoints, Vehicle vehicle)
    : waypoints_(validated(std::move(waypoints))),
      vehicle_(vehicle),
      position_splines_(make_position_splines(waypoints_)),
      yaw_spline_(make_yaw_spline(waypoints_)) {}

double Trajectory::clamp_time(double t) const {
  return std::clamp(t, start_time(), end_time());
}

Pose Trajectory::pose_at(double t) const {
  t = clamp_time(t);
  Pose pose;
  pose.stamp = t;
  for (int axis = 0; axis < 3; ++axis) pose.position[axis] = position_splines_[axis].value(t);
  pose.orientation = orientation_at(t);
  return pose;
}

Vec3 Trajectory::velocity_at(double t) const {
  t = clamp_time(t);
  return {position_splines_[0].first_derivative(t), position_splines_[1].first_derivative(t),
          position_splines_[2].first_derivative(t)};
}

Vec3 Trajectory::acceleration_at(double t) const {
  t = clamp_time(t);
  return {position_splines_[0].second_derivative(t), position_splines_[1].second_derivative(t),
          position_splines_[2].second_derivative(t)};
}

double Trajectory::yaw_at(double t) const {
  return yaw_spline_.value(clamp_time(t));
}

Eigen::Quaterniond Trajectory::orientation_at(double t) const {
  if (vehicle_ == Vehicle::ground) {
    return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_at(t), Vec3::UnitZ()));
  }
  return multirotor_orientation(acceleration_at(t), yaw_at(t));
}

// From the relative rotation over a short interval inside the flight (central where possible).
Vec3 Trajectory::angular_velocity_at(double t) const {
  constexpr double kHalfStep = 1e-4;  // s
  t = clamp_time(t);
  const double before = std::max(t - kHalfStep, start_time());
  const double after = std::min(t + kHalfStep, end_time());
  const Eigen::AngleAxisd relative(orientation_at(before).conjugate() * orientation_at(after));
  return relative.axis() * relative.angle() / (after - before);
}

}  // namespace uavslam::sim
