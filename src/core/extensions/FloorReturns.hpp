// A tilted scanner's floor strikes (beyond the seed). A multirotor tilts into every acceleration
// (20 degrees at 3.6 m/s^2), and its level beams then strike the floor a few metres ahead: points
// on the floor that the ICP, which reads every level beam as a wall (icp.split_axes), pairs with
// walls and the floor beams of the map, and that a keyframe would add to the map as walls. Where
// the scanner's floor beams measure the floor's level (the median height of its downward beams'
// points), a level beam's point less than `margin` above it is set aside: it lies on the floor.
// Returns on furniture tops or the ceiling stay (nothing here measures their level).
#pragma once

#include <cstddef>

#include "core/ScanProjection.hpp"

namespace uavslam {

// Removes from `scan` the level beams' points within `margin` (m) of the floor's level and
// returns how many; none where fewer than three downward beams saw the floor.
std::size_t set_aside_floor_returns(ProjectedScan& scan, double margin);

}  // namespace uavslam
