// How far below the body the floor is, as a scan's floor beams (a mirror's, aimed down) see it
// (beyond the seed): the median depth of their points, which a few beams on a box or a cable do
// not move, and the median's variance from the beams' spread:
//   below = median_i(-z_i),   var = (pi / 2) (1.4826 MAD)^2 / n
// (z_i: a downward beam's point relative to the body, world-oriented; 1.4826 MAD: a normal
// spread's sigma; pi / 2: the median's variance against the mean's). Shared by FloorReturns (what
// lies on the floor) and FloorLevel (the height from the floor).
#pragma once

#include <cstddef>
#include <optional>

#include "core/ScanProjection.hpp"

namespace uavslam {

struct FloorSighting {
  double below = 0.0;     // m, the floor's depth under the body (positive)
  double variance = 0.0;  // m^2, of `below`
  std::size_t beams = 0;  // downward beams that saw it
};

// None where fewer than three downward beams returned.
std::optional<FloorSighting> floor_below(const ProjectedScan& scan);

}  // namespace uavslam
