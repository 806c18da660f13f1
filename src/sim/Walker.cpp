#include "sim/Walker.hpp"

#include <cmath>

namespace uavslam::sim {

namespace {

double path_length(const std::vector<Eigen::Vector2d>& path) {
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length;
}

// The point `s` m along the path (0 <= s <= its length).
Eigen::Vector2d point_along(const std::vector<Eigen::Vector2d>& path, double s) {
  for (std::size_t i = 1; i < path.size(); ++i) {
    const double leg = (path[i] - path[i - 1]).norm();
    if (s <= leg && leg > 0.0) return path[i - 1] + (path[i] - path[i - 1]) * (s / leg);
    s -= leg;
  }
  return path.back();
}

}  // namespace

Cylinder walker_at(const Walker& walker, double t) {
  const double length = path_length(walker.path);
  // Folded onto one round trip: 0 -> L out, L -> 2 L back.
  double s = length > 0.0 ? std::fmod(walker.start + walker.speed * t, 2.0 * length) : 0.0;
  if (s < 0.0) s += 2.0 * length;
  if (s > length) s = 2.0 * length - s;
  Cylinder body;
  body.center = point_along(walker.path, s);
  body.radius = walker.radius;
  body.z0 = 0.0;
  body.z1 = walker.height;
  return body;
}

}  // namespace uavslam::sim
