// What a blind direction's few structures say (beyond the seed; issue 17). A direction is flagged
// degenerate by its share of the scan's information (ScanInformation), yet a door jamb, a pilaster
// or an end wall can fix it to a centimetre where the motion prior has drifted a metre. Their
// pairs are too few to be trusted as the ICP left them (a point-to-line match slides along the
// walls, and its Hessian cannot tell a true jamb from a look-alike), so the direction e is
// searched: the scan, held where the ICP put it across e, is shifted along e over the prior's
// extent, and at each shift s the ICP's point-to-line cost of the beams that face e (their scan
// normal within 60 degrees of it: a wall along e only adds the jitter of the map points it slides
// over) is summed, each residual capped at c^2:
//   C(s) = sum_i min((n_i . (m_i + s e - d_i(s)))^2, c^2)
// (a one-dimensional correlative search, Olson 2009, in the ICP's metric). A beam's pair d_i(s) is
// its nearest map point across the floor (horizontal distance: a jamb's face stands over the
// storey, and the keyframe that holds it best may have been flown at another height) among those
// whose normal faces the way the beam's does (within 30 degrees: a jamb pairs with a jamb, not
// with the wall beside it or its own back) and that the caller allows (not a keyframe no better
// placed along e than the vehicle: its copy of a jamb would only confirm the drift); it counts
// c^2 with none within max_distance. The fix is
// the deepest dip, taken only when it is unique (the deepest minimum elsewhere, beyond
// `exclusion`, no deeper than `uniqueness` of it), deep (min_points and half the facing beams'
// worth of c^2), sharp against the jitter of C away from it (`contrast` median absolute
// deviations) and held by min_points distinct map points; otherwise the direction stays blind.
// It is refined by Gauss-Newton along e (the capped pairs left out), which gives its information
// sum_i (n_i . e)^2.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "core/ScanMatcher.hpp"
#include "core/WorldMap.hpp"

namespace uavslam {

struct BlindSearchOptions {
  double half_width = 1.0;       // m: the shifts searched, -half_width..half_width
  double step = 0.02;            // m between shifts
  double cap = 0.03;             // m: c, a pair's residual counted at most this
  double max_distance = 0.3;     // m: a farther nearest map point is no pair
  double contrast = 8.0;         // the dip's depth, in median absolute deviations of C
  double uniqueness = 0.5;       // the deepest other minimum at most this fraction of the depth
  double exclusion = 0.1;        // m: minima this close to the best are its own
  int refine_iterations = 3;     // Gauss-Newton steps along e at the best shift
  double facing = 0.5;           // a point whose scan normal is within 60 degrees of e faces it
  double normals_agree = 0.866;  // a pair's map normal within 30 degrees of the scan's
  std::size_t min_points = 4;    // facing points, and the dip's depth in fitting points (c^2 each)
};

struct DirectionFix {
  double offset = 0.0;         // m along e from where the scan was given
  double information = 0.0;    // 1/m^2 in units of the residual variance: sum_i (n_i . e)^2
  std::size_t map_points = 0;  // distinct map points the pairs took
  double uniqueness = 0.0;     // the deepest other minimum's depth over the best's
};

// Which map points a pair may take (by map index): those placed better along the direction than
// the prior places the vehicle; every one when empty.
using MapPointFilter = std::function<bool(std::size_t)>;

// The fix along `direction` for the scan points `scan` placed at the prior's position along it
// (world frame), or none when the search finds no single clear dip.
std::optional<DirectionFix> search_blind_direction(const WorldMap& map, const ScanPoints& scan,
                                                   const Vec3& direction,
                                                   const BlindSearchOptions& options,
                                                   const MapPointFilter& usable = {});

}  // namespace uavslam
