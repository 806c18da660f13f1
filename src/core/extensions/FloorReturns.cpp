#include "core/extensions/FloorReturns.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace uavslam {
namespace {

constexpr std::size_t kMinFloorPoints = 3;

}  // namespace

std::size_t set_aside_floor_returns(ProjectedScan& scan, double margin) {
  std::vector<double> floor;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (scan.vertical[i] && scan.points[i].z() < 0.0) floor.push_back(scan.points[i].z());
  }
  if (floor.size() < kMinFloorPoints) return 0;
  const auto middle = floor.begin() + std::ptrdiff_t(floor.size() / 2);
  std::nth_element(floor.begin(), middle, floor.end());
  const double level = *middle + margin;

  std::size_t kept = 0;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (!scan.vertical[i] && scan.points[i].z() < level) continue;
    scan.points[kept] = scan.points[i];
    scan.vertical[kept] = scan.vertical[i];
    ++kept;
  }
  const std::size_t removed = scan.points.size() - kept;
  scan.points.resize(kept);
  scan.vertical.resize(kept);
  return removed;
}

}  // namespace uavslam
