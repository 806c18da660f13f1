// The horizontal normal of the wall under each point of a scan, for the point-to-line metric: a
// planar scan is ordered by beam angle, so a point's neighbours along the scan lie on the same wall
// unless a gap separates them. A line fitted to them (principal axes of their 2D scatter) gives
// the wall's direction; the normal is perpendicular to it.
#pragma once

#include <vector>

#include "core/Types.hpp"

namespace uavslam {

struct SurfaceNormalOptions {
  int half_window = 2;             // neighbours on each side along the scan
  double max_neighbour_gap = 0.2;  // m; a neighbour farther from the point is another surface
  double max_flatness = 0.1;       // smallest / largest scatter eigenvalue above this: no line
};

// One unit normal (z = 0) per point, facing the scanner (the points are relative to it), or zero
// where no line fits (too few neighbours, a corner, a beam that points up or down). `vertical`
// marks beams whose points carry no wall.
std::vector<Vec3> estimate_normals(const Points& ordered_points, const std::vector<bool>& vertical,
                                   const SurfaceNormalOptions& options = {});

}  // namespace uavslam
