#include "core/extensions/FloorReturns.hpp"

#include <optional>

#include "core/extensions/FloorBelow.hpp"

namespace uavslam {

std::size_t set_aside_floor_returns(ProjectedScan& scan, double margin) {
  const std::optional<FloorSighting> floor = floor_below(scan);
  if (!floor) return 0;
  const double level = -floor->below + margin;

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
