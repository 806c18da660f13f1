// The height from the floor's level (beyond the seed). The floor beams pair with the map's floor
// points, so over floor the map has seen the height is measured against the map; over floor it
// has not (a hall, a long corridor), only against the last keyframe's floor, and the height is
// chained from keyframe to keyframe: it walks, as the position does in a blind corridor (hall.yaml:
// 0.1 m over 100 s). But a storey's floor is one level, flat to a centimetre or so over metres
// (DIN 18202's tolerances), and the floor seen now is most likely the floor taken off from: an
// absolute height, as an autopilot's rangefinder gives. The level is taken once, over the scans
// of the first `window` seconds (the map's height is exact there, the vehicle near take-off):
//   L = mean_k (z_k - below_k)
// and afterwards a floor whose level, as the chained height puts it, is within `gate` of L is the
// same floor, and measures the height:
//   z = L + below,   var = var(below) + flatness^2 + var(L)
// Farther (a step, a ramp, a crate's top, another storey) it is not, and the height stays chained.
#pragma once

#include <cstddef>
#include <optional>

#include "core/extensions/FloorBelow.hpp"

namespace uavslam {

struct HeightFix {
  double height = 0.0;    // m, the body's, in the map
  double variance = 0.0;  // m^2
};

class FloorLevel {
 public:
  // window: s of scans the level is taken over, from the first that sees the floor; gate: m;
  // flatness: m, how far the floor's level may differ from place to place (a sigma).
  FloorLevel(double window, double gate, double flatness)
      : window_(window), gate_(gate), flatness_(flatness) {}

  // The floor seen `floor.below` under the body at the height z the match gave it (the map's).
  // While the level is taken: joins it, no fix. Afterwards: the height it measures, if it is the
  // level's floor.
  std::optional<HeightFix> add(double stamp, double z, const FloorSighting& floor);

  bool settled() const { return settled_; }
  double level() const { return n_ > 0 ? sum_ / double(n_) : 0.0; }  // m, L
  double level_variance() const;                                     // m^2, var(L)

 private:
  double window_;
  double gate_;
  double flatness_;
  std::optional<double> start_;
  std::size_t n_ = 0;  // levels so far, their sum and the sum of the sightings' variances
  double sum_ = 0.0;
  double variances_ = 0.0;
  bool settled_ = false;
};

}  // namespace uavslam
