// The heading of a body: its rotation about the vertical. A yaw kept on top of the orientation
// source (SlamPipeline's heading correction), the planar trajectories of 2D logs (x y theta), and
// wheel odometry's theta all meet here.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/Types.hpp"

namespace uavslam {

// The rotation by `yaw` rad about the vertical (world z).
inline Eigen::Quaterniond yaw_rotation(double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Vec3::UnitZ()));
}

// Where the body's x axis points in the horizontal plane, rad in (-pi, pi].
inline double heading_of(const Eigen::Quaterniond& orientation) {
  const Vec3 forward = orientation * Vec3::UnitX();
  return std::atan2(forward.y(), forward.x());
}

// How far the body's vertical axis leans from the world's, rad in [0, pi].
inline double tilt_of(const Eigen::Quaterniond& orientation) {
  return std::acos(std::clamp((orientation * Vec3::UnitZ()).z(), -1.0, 1.0));
}

}  // namespace uavslam
