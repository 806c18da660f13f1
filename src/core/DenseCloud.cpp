#include "core/DenseCloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
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

namespace {

// Voxel indices within +-2^20 per axis (+-10 km at 1 cm) pack into 21 bits each.
constexpr int kKeyBits = 21;
constexpr std::int64_t kKeyOffset = std::int64_t{1} << (kKeyBits - 1);

std::uint64_t packed_key(const Eigen::Array3d& cell) {
  std::uint64_t key = 0;
  for (int axis = 0; axis < 3; ++axis) {
    key = (key << kKeyBits) | std::uint64_t(std::int64_t(cell[axis]) + kKeyOffset);
  }
  return key;
}

// Fibonacci hashing: the multiplication spreads neighbouring keys over the table.
std::size_t slot_of(std::uint64_t key, std::size_t mask) {
  return std::size_t((key * 0x9E3779B97F4A7C15ull) >> 20) & mask;
}

}  // namespace

DenseCloud::Voxel& DenseCloud::voxel_at(std::uint64_t key) {
  if (2 * (voxels_.size() + 1) > keys_.size()) grow();
  const std::size_t mask = keys_.size() - 1;
  std::size_t slot = slot_of(key, mask);
  while (keys_[slot] != kEmpty && keys_[slot] != key) slot = (slot + 1) & mask;
  if (keys_[slot] == kEmpty) {
    keys_[slot] = key;
    slots_[slot] = std::uint32_t(voxels_.size());
    voxels_.emplace_back();
  }
  return voxels_[slots_[slot]];
}

void DenseCloud::grow() {
  const std::vector<std::uint64_t> old_keys = std::move(keys_);
  const std::vector<std::uint32_t> old_slots = std::move(slots_);
  const std::size_t capacity = std::max<std::size_t>(1024, 2 * old_keys.size());
  keys_.assign(capacity, kEmpty);
  slots_.assign(capacity, 0);
  const std::size_t mask = capacity - 1;
  for (std::size_t i = 0; i < old_keys.size(); ++i) {
    if (old_keys[i] == kEmpty) continue;
    std::size_t slot = slot_of(old_keys[i], mask);
    while (keys_[slot] != kEmpty) slot = (slot + 1) & mask;
    keys_[slot] = old_keys[i];
    slots_[slot] = old_slots[i];
  }
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
  const Eigen::Array3d cell = (position / voxel_).array().floor();
  // Beyond the packed key's range is no map of a building: dropped (not counted as added).
  if ((cell.abs() >= double(kKeyOffset)).any()) {
    --points_added_;
    return;
  }
  Voxel& v = voxel_at(packed_key(cell));
  if (v.count == 0) v.first_time = time;
  v.sum += position;
  v.intensity_sum += intensity;
  ++v.count;
}

std::vector<DensePoint> DenseCloud::points() const {
  if (voxel_ <= 0.0) return unfiltered_;
  std::vector<DensePoint> points;
  points.reserve(voxels_.size());
  for (const Voxel& v : voxels_) {
    points.push_back({v.sum / v.count, float(v.intensity_sum / v.count), v.first_time});
  }
  return points;
}

std::size_t DenseCloud::size() const {
  return voxel_ <= 0.0 ? unfiltered_.size() : voxels_.size();
}

}  // namespace uavslam
