#include "eval/TruthRelations.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/Angles.hpp"
#include "core/PlanarPose.hpp"

namespace uavslam::eval {
namespace {

Relation relation(const PlanarStamped& a, const PlanarStamped& b) {
  const PlanarPose m = motion_between({a.x, a.y, a.theta}, {b.x, b.y, b.theta});
  return {a.t, b.t, m.x, m.y, m.theta};
}

// The scans one step apart along the path, the first included.
std::vector<std::size_t> steps(const std::vector<PlanarStamped>& truth,
                               const TruthRelationOptions& options) {
  std::vector<std::size_t> chosen;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (!chosen.empty()) {
      const PlanarStamped& last = truth[chosen.back()];
      const double moved = std::hypot(truth[i].x - last.x, truth[i].y - last.y);
      const double turned = std::abs(wrap_angle(truth[i].theta - last.theta));
      if (moved < options.step_length && turned < options.step_turn) continue;
    }
    chosen.push_back(i);
  }
  return chosen;
}

}  // namespace

std::vector<Relation> relations_from_truth(const std::vector<PlanarStamped>& truth,
                                           const TruthRelationOptions& options) {
  const std::vector<std::size_t> chosen = steps(truth, options);
  std::vector<Relation> relations;
  for (std::size_t k = 1; k < chosen.size(); ++k) {
    relations.push_back(relation(truth[chosen[k - 1]], truth[chosen[k]]));
  }
  const std::size_t every = static_cast<std::size_t>(std::max(options.revisit_every, 1));
  for (std::size_t k = 0; k < chosen.size(); k += every) {
    const PlanarStamped& later = truth[chosen[k]];
    for (std::size_t e = 0; e < k; ++e) {
      const PlanarStamped& earlier = truth[chosen[e]];
      if (later.t - earlier.t < options.revisit_after) break;
      const double apart = std::hypot(later.x - earlier.x, later.y - earlier.y);
      const double turned = std::abs(wrap_angle(later.theta - earlier.theta));
      if (apart <= options.revisit_distance && turned <= options.revisit_turn) {
        relations.push_back(relation(earlier, later));
        break;
      }
    }
  }
  return relations;
}

}  // namespace uavslam::eval
