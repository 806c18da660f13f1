#include "core/ScanProjection.hpp"

#include <cmath>

namespace uavslam {
bool is_valid_range(float range, const ScanGeometry& geometry) {
  return std::isfinite(range) && range >= geometry.min_range && range <= geometry.max_range;
}

SweptSensor::SweptSensor(const ScanGeometry& geometry, const Eigen::Quaterniond& orientation,
                         const SweepMotion& sweep, const Vec3& position)
    : geometry_(&geometry),
      deskew_(sweep.moving() && geometry.fire_times.size() == geometry.directions.size()),
      orientation_(orientation.toRotationMatrix()),
      rate_(sweep.angular_velocity.norm()),
      velocity_(sweep.velocity),
      position_(position) {
  // Sensor frame to the world in one transform: the body's pose, then the mount.
  Eigen::Isometry3d body = Eigen::Isometry3d::Identity();
  body.linear() = orientation_;
  at_stamp_ = Eigen::Translation3d(position) * body * geometry.mount;
  if (rate_ > 0.0) axis_ = sweep.angular_velocity / rate_;
}

namespace {

// Rodrigues' formula: v turned by the angle whose cosine and sine are c and s about the unit axis.
inline Vec3 turned(const Vec3& v, const Vec3& axis, double c, double s) {
  return c * v + s * axis.cross(v) + (1.0 - c) * axis.dot(v) * axis;
}

}  // namespace

// Fired t_i after the stamp: the body had turned by Exp(omega t_i) (body frame, so after the
// orientation) and moved by v t_i (world frame). The beam leaves the mount's origin m along
// M d: p_i = position + R Exp(omega t_i) (m + r M d) + v t_i.
Vec3 SweptSensor::point(std::size_t i, double range, Vec3* direction) const {
  const Vec3& d = geometry_->directions[i];
  if (!deskew_) {
    if (direction) *direction = at_stamp_.linear() * d;
    return at_stamp_ * (range * d);
  }
  const double t = geometry_->fire_times[i];
  const double c = std::cos(rate_ * t);
  const double s = std::sin(rate_ * t);
  const Vec3 beam = orientation_ * turned(geometry_->mount.linear() * d, axis_, c, s);
  if (direction) *direction = beam;
  const Vec3 origin = orientation_ * turned(geometry_->mount.translation(), axis_, c, s);
  return position_ + origin + range * beam + velocity_ * t;
}

ProjectedScan project_scan(const Scan& scan, const Eigen::Quaterniond& orientation,
                           const SweepMotion& sweep) {
  const ScanGeometry& geometry = *scan.geometry;
  const SweptSensor sensor(geometry, orientation, sweep);
  ProjectedScan projected;
  projected.points.reserve(scan.ranges.size());
  projected.vertical.reserve(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (!is_valid_range(r, geometry)) {
      ++projected.invalid;
      continue;
    }
    Vec3 direction;
    projected.points.push_back(sensor.point(i, double(r), &direction));
    projected.vertical.push_back(is_vertical(direction));
  }
  return projected;
}

}  // namespace uavslam
