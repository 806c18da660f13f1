// Steps 1 and 2 of the pipeline: a scan's ranges become 3D points, rotated into the world frame
// by the orientation source (the seed trusts the IMU for rotation), then thinned to every k-th.
#pragma once

#include <cstddef>
#include <vector>

#include "core/Types.hpp"

namespace uavslam {

// A return is usable when it is finite and within the sensor's [min_range, max_range].
bool is_valid_range(float range, const ScanGeometry& geometry);

struct ProjectedScan {
  Points points;  // world-oriented, relative to the body origin (translation not applied)
  std::vector<bool> vertical;  // per point: the beam points more up/down than sideways (> 45 deg)
  std::size_t invalid = 0;     // ranges dropped as NaN, inf or out of range
};

// p = R_imu * (mount * (r * direction)): each valid beam in the world orientation.
ProjectedScan project_scan(const Scan& scan, const Eigen::Quaterniond& orientation);

// Keep every k-th point (seed: k = 5, 216 of 1080), starting with the first.
template <typename T>
std::vector<T> keep_every_kth(const std::vector<T>& items, int k) {
  if (k <= 1) return items;
  std::vector<T> kept;
  kept.reserve(items.size() / std::size_t(k) + 1);
  for (std::size_t i = 0; i < items.size(); i += std::size_t(k)) kept.push_back(items[i]);
  return kept;
}

}  // namespace uavslam
