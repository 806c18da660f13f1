#include "core/DenseCloud.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/ScanProjection.hpp"

namespace uavslam {

DenseCloud::DenseCloud(double voxel) : voxel_(voxel) {
  if (!std::isfinite(voxel)) {
    throw std::invalid_argument("dense cloud voxel size must be finite, got " +
                                std::to_string(voxel));
  }
}

std::size_t DenseCloud::KeyHash::operator()(const Eigen::Vector3i& key) const {
  // The spatial hash of Teschner et al. (2003), as KISS-ICP's VoxelHashMap uses.
  return std::size_t(key.x()) * 73856093u ^ std::size_t(key.y()) * 19349663u ^
         std::size_t(key.z()) * 83492791u;
}

void DenseCloud::add_scan(const Scan& scan, const Pose& pose) {
  const ScanGeometry& geometry = *scan.geometry;
  const bool has_intensity = scan.intensities.size() == scan.ranges.size();
  const Eigen::Isometry3d sensor_to_world =
      Eigen::Translation3d(pose.position) * pose.orientation * geometry.mount;
  const std::size_t beams = std::min(scan.ranges.size(), geometry.directions.size());
  for (std::size_t i = 0; i < beams; ++i) {
    if (!is_valid_range(scan.ranges[i], geometry)) continue;
    const Vec3 p = sensor_to_world * (double(scan.ranges[i]) * geometry.directions[i]);
    add_point(p, has_intensity ? scan.intensities[i] : 0.0f, scan.stamp);
  }
}

void DenseCloud::add_point(const Vec3& position, float intensity, double time) {
  if (!position.allFinite()) return;
  ++points_added_;
  if (voxel_ <= 0.0) {
    unfiltered_.push_back({position, intensity, time});
    return;
  }
  const Eigen::Array3d cell_index = (position / voxel_).array().floor();
  // A key must fit an int: farther than ~2e9 voxels from the origin is no map of a building.
  if ((cell_index.abs() > 2e9).any()) return;
  const Eigen::Vector3i key = cell_index.cast<int>();
  Voxel& cell = voxels_[key];
  if (cell.count == 0) cell.first_time = time;
  cell.sum += position;
  cell.intensity_sum += intensity;
  ++cell.count;
}

std::vector<DensePoint> DenseCloud::points() const {
  if (voxel_ <= 0.0) return unfiltered_;
  std::vector<DensePoint> points;
  points.reserve(voxels_.size());
  for (const auto& [key, cell] : voxels_) {
    points.push_back(
        {cell.sum / cell.count, float(cell.intensity_sum / cell.count), cell.first_time});
  }
  // Scan order, as a reader of the cloud expects; the hash map's order is arbitrary.
  std::sort(points.begin(), points.end(), [](const DensePoint& a, const DensePoint& b) {
    if (a.time != b.time) return a.time < b.time;
    return std::lexicographical_compare(a.position.data(), a.position.data() + 3, b.position.data(),
                                        b.position.data() + 3);
  });
  return points;
}

std::size_t DenseCloud::size() const {
  return voxel_ <= 0.0 ? unfiltered_.size() : voxels_.size();
}

}  // namespace uavslam
