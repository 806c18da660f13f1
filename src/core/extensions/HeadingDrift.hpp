// How far the map's heading walks from one keyframe to the next (beyond the seed), learnt from the
// heading checks (icp.heading: periodic_check: every heading_check_every scans and before every
// keyframe). A check measures the disagreement d_k of the heading with the map where the vehicle
// is. A steady source's d_k is the match's own yaw noise, white from one check to the next; a
// drifting source turns away from the map between the corrections and its d_k persists, and the
// keyframes made meanwhile join the map turned by it. The persistent part's mean square is the
// disagreements' lag-one autocovariance, which white noise does not reach:
//   q = mean_k (d_k d_{k-1}),   0 while negative
// The map's heading so walks by q (rad^2) per keyframe. Checks made while hovering see the same
// pairs and share their noise too, so q comes out high at take-off (docs/algorithm.md).
#pragma once

#include <cstddef>
#include <optional>

namespace uavslam {

class HeadingDrift {
 public:
  // A check's disagreement (rad), whether or not it corrected the heading.
  void add_check(double disagreement);
  // q above (rad^2); 0 before two checks.
  double variance_per_keyframe() const;

 private:
  std::optional<double> last_;
  double sum_ = 0.0;  // of d_k d_{k-1}
  std::size_t count_ = 0;
};

}  // namespace uavslam
