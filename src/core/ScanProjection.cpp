#include "core/ScanProjection.hpp"

#include <cmath>

namespace uavslam {
bool is_valid_range(float range, const ScanGeometry& geometry) {
  return std::isfinite(range) && range >= geometry.min_range && range <= geometry.max_range;
}

ProjectedScan project_scan(const Scan& scan, const Eigen::Quaterniond& orientation) {
  const ScanGeometry& geometry = *scan.geometry;
  // Sensor frame to the world orientation in one transform: rotation of the body, then the mount.
  Eigen::Isometry3d sensor_to_world = Eigen::Isometry3d::Identity();
  sensor_to_world.linear() = orientation.toRotationMatrix();
  sensor_to_world = sensor_to_world * geometry.mount;

  ProjectedScan projected;
  projected.points.reserve(scan.ranges.size());
  projected.vertical.reserve(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (!is_valid_range(r, geometry)) {
      ++projected.invalid;
      continue;
    }
    const Vec3 direction = sensor_to_world.linear() * geometry.directions[i];
    projected.points.push_back(sensor_to_world * (double(r) * geometry.directions[i]));
    projected.vertical.push_back(is_vertical(direction));
  }
  return projected;
}

}  // namespace uavslam
