#include "maps/DenseCloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/ScanProjection.hpp"

namespace uavslam {
namespace {

// Voxel indices within +-2^20 per axis (+-10 km at 1 cm) pack into 21 bits each.
constexpr int kKeyBits = 21;
constexpr std::int64_t kKeyOffset = std::int64_t{1} << (kKeyBits - 1);
// How many points ahead the table is prefetched: a scan's points land in scattered slots, and
// fetching them while the earlier ones are summed hides most of the memory's latency.
constexpr std::size_t kPrefetchAhead = 16;

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

DenseCloud::DenseCloud(double voxel) : voxel_(voxel) {
  if (!std::isfinite(voxel)) {
    throw std::invalid_argument("dense cloud voxel size must be finite, got " +
                                std::to_string(voxel));
  }
}

void DenseCloud::add_scan(const Scan& scan, const Pose& pose, const SweepMotion& sweep) {
  const ScanGeometry& geometry = *scan.geometry;
  const bool has_intensity = scan.intensities.size() == scan.ranges.size();
  const SweptSensor sensor(geometry, pose.orientation, sweep, pose.position);
  const std::size_t beams = std::min(scan.ranges.size(), geometry.directions.size());
  placed_.clear();
  for (std::size_t i = 0; i < beams; ++i) {
    if (!is_valid_range(scan.ranges[i], geometry)) continue;
    const Vec3 p = sensor.point(i, double(scan.ranges[i]));
    const float intensity = has_intensity ? scan.intensities[i] : 0.0f;
    if (voxel_ <= 0.0) {
      add_point(p, intensity, scan.stamp);
    } else if (Placed placed; place(p, intensity, placed)) {
      placed_.push_back(placed);
    }
  }
  make_room_for(placed_.size());
  const std::size_t mask = table_.size() - 1;
  for (std::size_t i = 0; i < placed_.size(); ++i) {
    if (i + kPrefetchAhead < placed_.size()) {
      __builtin_prefetch(&table_[slot_of(placed_[i + kPrefetchAhead].key, mask)]);
    }
    accumulate(placed_[i], scan.stamp);
  }
}

void DenseCloud::add_point(const Vec3& position, float intensity, double time) {
  if (voxel_ <= 0.0) {
    if (!position.allFinite()) return;
    ++points_added_;
    unfiltered_.push_back({position, intensity, time});
    return;
  }
  Placed placed;
  if (!place(position, intensity, placed)) return;
  make_room_for(1);
  accumulate(placed, time);
}

// Beyond the packed key's range is no map of a building: such points, and non-finite ones, are
// dropped (not counted as added).
bool DenseCloud::place(const Vec3& position, float intensity, Placed& placed) const {
  if (!position.allFinite()) return false;
  const Eigen::Array3d cell = (position / voxel_).array().floor();
  if ((cell.abs() >= double(kKeyOffset)).any()) return false;
  placed = {packed_key(cell), position - cell.matrix() * voxel_, intensity};
  return true;
}

void DenseCloud::accumulate(const Placed& placed, double time) {
  const std::size_t mask = table_.size() - 1;
  std::size_t i = slot_of(placed.key, mask);
  while (table_[i].key != kEmpty && table_[i].key != placed.key) i = (i + 1) & mask;
  Voxel& v = table_[i];
  if (v.key == kEmpty) {
    v.key = placed.key;
    v.order = std::uint32_t(voxel_count_++);
    v.first_time = time;
  }
  for (int axis = 0; axis < 3; ++axis) v.sum[axis] += float(placed.offset[axis]);
  v.intensity_sum += placed.intensity;
  ++v.count;
  ++points_added_;
}

// The table stays at most half full, so probes stay short.
void DenseCloud::make_room_for(std::size_t more_voxels) {
  if (2 * (voxel_count_ + more_voxels) <= table_.size()) return;
  std::size_t capacity = std::max<std::size_t>(1024, table_.size());
  while (2 * (voxel_count_ + more_voxels) > capacity) capacity *= 2;
  const std::vector<Voxel, HugePageAllocator<Voxel>> old = std::move(table_);
  table_.assign(capacity, Voxel{});
  const std::size_t mask = capacity - 1;
  for (const Voxel& v : old) {
    if (v.key == kEmpty) continue;
    std::size_t i = slot_of(v.key, mask);
    while (table_[i].key != kEmpty) i = (i + 1) & mask;
    table_[i] = v;
  }
}

Vec3 DenseCloud::corner_of(std::uint64_t key) const {
  Vec3 corner;
  for (int axis = 2; axis >= 0; --axis) {
    const auto field = std::int64_t(key & ((std::uint64_t{1} << kKeyBits) - 1));
    corner[axis] = double(field - kKeyOffset) * voxel_;
    key >>= kKeyBits;
  }
  return corner;
}

std::vector<DensePoint> DenseCloud::points() const {
  if (voxel_ <= 0.0) return unfiltered_;
  std::vector<DensePoint> points(voxel_count_);
  for (const Voxel& v : table_) {
    if (v.key == kEmpty) continue;
    const Vec3 mean_offset = Vec3(v.sum[0], v.sum[1], v.sum[2]) / v.count;
    points[v.order] = {corner_of(v.key) + mean_offset, v.intensity_sum / float(v.count),
                       v.first_time};
  }
  return points;
}

std::size_t DenseCloud::size() const {
  return voxel_ <= 0.0 ? unfiltered_.size() : voxel_count_;
}

}  // namespace uavslam
