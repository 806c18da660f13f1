// A pose in the plane (x, y and the heading) and the planar pose algebra of Smith, Self &
// Cheeseman: a ⊕ b and a⁻¹ ⊕ b. What the 2D logs' estimates and relations, and wheel odometry,
// are made of.
#pragma once

#include <cmath>

#include "core/Heading.hpp"
#include "core/Types.hpp"

namespace uavslam {

struct PlanarPose {
  double x = 0.0, y = 0.0, theta = 0.0;  // m, m, rad
};

// The angle in [-pi, pi] equivalent to `angle`.
inline double normalised_angle(double angle) {
  return std::atan2(std::sin(angle), std::cos(angle));
}

// a⁻¹ ⊕ b: b seen from a (the motion from a to b, in the frame of a).
inline PlanarPose motion_between(const PlanarPose& a, const PlanarPose& b) {
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double c = std::cos(a.theta);
  const double s = std::sin(a.theta);
  return {c * dx + s * dy, -s * dx + c * dy, normalised_angle(b.theta - a.theta)};
}

// a ⊕ b: motion b applied after pose a.
inline PlanarPose compose(const PlanarPose& a, const PlanarPose& b) {
  const double c = std::cos(a.theta);
  const double s = std::sin(a.theta);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, normalised_angle(a.theta + b.theta)};
}

inline PlanarPose inverse(const PlanarPose& a) {
  return motion_between(a, {});
}

// A body pose in the plane: its position's x and y, its heading.
inline PlanarPose planar_pose(const Pose& pose) {
  return {pose.position.x(), pose.position.y(), heading_of(pose.orientation)};
}

}  // namespace uavslam
