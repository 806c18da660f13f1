#include "core/extensions/FloorReturns.hpp"

#include <optional>

#include "core/extensions/FloorBelow.hpp"

namespace uavslam {

std::size_t set_aside_floor_returns(ProjectedScan& scan, double margin) {
  const std::optional<FloorSighting> floor = floor_below(scan);
  if (!floor) return 0;
  const double level = -floor->below + margin;

  return remove_points(scan, [&scan, level](std::size_t i) {
    return !scan.vertical[i] && scan.points[i].z() < level;
  });
}

}  // namespace uavslam
