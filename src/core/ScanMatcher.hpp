// The seed's translation-only ICP (thesis ch. 5.4.3.1, Figure 5.15): the scan's rotation comes from
// the orientation source, the matcher finds only where the scan sits in the world map.
//
//   error before (eq. 5.18) -> [find nearest points -> best translation (eq. 5.16) -> apply]
//   x a fixed number of iterations (stop if the correction grows erroneously large)
//   -> error after (eq. 5.18) -> accept or skip the scan
//
// Each pair carries the weights omega of eq. 5.17, one per axis. The seed weighs uniformly (1 on
// every axis); with split axes a level beam's pair informs only x-y and a floor beam's only z.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/Correspondences.hpp"
#include "core/ScanOutcome.hpp"
#include "core/SlamConfig.hpp"
#include "core/WorldMap.hpp"
#include "core/extensions/PlanarCorrection.hpp"
#include "core/extensions/ScanInformation.hpp"

namespace uavslam {

// The scan points m_i that take part, each with its per-axis weight omega_i (0 or 1 per axis).
struct ScanPoints {
  Points points;
  std::vector<Vec3> weights;
  std::vector<Vec3> normals;  // empty (the seed), or each point's wall normal (ScanInformation)
};

// Uniform weights (the seed) or split ones (level beams x-y, vertical beams z).
ScanPoints weigh_points(Points points, const std::vector<bool>& vertical, bool split_axes);

// Step 1: pair each scan point with its nearest map point; pairs whose weighted distance exceeds
// max_distance get omega = 0 and are left out (max_distance <= 0: keep all, as the seed does).
// Where the map holds surface normals the pairs carry them (the point-to-line metric).
// `nearest` carries the neighbours from one iteration to the next: empty, they are searched
// afresh; filled for these points, the search starts from them.
Correspondences find_nearest_points(const WorldMap& map, const ScanPoints& scan,
                                    double max_distance, std::vector<Neighbour>& nearest);
Correspondences find_nearest_points(const WorldMap& map, const ScanPoints& scan,
                                    double max_distance);

// Beyond the seed (icp.refine_lines_only): with the point-to-line metric, a pair whose map point
// has no wall normal counts nothing horizontally (its x-y weights zeroed; a pair left with no
// weight at all is dropped). Such map points are a far wall's seen at a grazing angle, farther
// apart than the normals' gap, and corners. Counted point to point, the offset to the nearest of
// them is where the map's points happen to lie, up to half their spacing (in a map of every 5th
// point, the seed's, 5-10 cm at 10-30 m), and not random: a vehicle moving along a wall meets the
// same pattern scan after scan, and the match turns by it keyframe after keyframe
// (docs/algorithm.md).
void drop_pairs_without_normal(Correspondences& pairs);

// Step 2, eq. 5.16 per axis k: t_k = sum_i w_ik (m_ik - d_ik) / sum_i w_ik, the weighted
// difference of the means c_m - c_d; 0 on an axis no pair informs. It minimises E(t).
Vec3 best_translation(const Correspondences& pairs);

// Eq. 5.18: E(t) = (1/N) sum_i sum_k w_ik (m_ik - (d_ik + t_k))^2, the mean squared distance;
// for a pair with a normal only the residual's component along it counts (point-to-line).
double error_function(const Correspondences& pairs, const Vec3& t = Vec3::Zero());

// Move the points by the correction (the scan onto the map: -t).
void apply_transform(Points& points, const Vec3& correction);

struct MatchResult {
  // Accepted, NoCorrespondences, TranslationTooLarge, ErrorTooLarge or ErrorIncreased.
  ScanOutcome outcome = ScanOutcome::NoCorrespondences;
  Vec3 position = Vec3::Zero();    // the body position the scan was aligned to
  Vec3 correction = Vec3::Zero();  // position - initial position
  double yaw = 0.0;                // rad; the heading correction found (0 unless estimated)
  double error_before = 0.0;       // m^2
  double error_after = 0.0;        // m^2
  int iterations = 0;
  std::size_t correspondences = 0;  // pairs in the final error
  Points aligned;                   // the scan's points in the world frame at `position`
  Correspondences pairs;            // the pairs of the final error (what the scan saw)
  // Beyond the seed: the yaw the scan could not see was held at the prediction's and the scan
  // matched again without it (SlamPipeline::yaw_blind).
  bool yaw_held = false;
  // What the pairs saw, the yaw estimated beside the translation, when SlamPipeline::yaw_blind
  // already worked it out (the pose's analysis takes it from here rather than again).
  std::optional<ScanInformation> information;
};

class ScanMatcher {
 public:
  explicit ScanMatcher(const SlamConfig::Icp& config);

  // scan: world-oriented points relative to the body origin; initial: the body position to start
  // from (the last position, as the seed, which has no motion model; or the caller's prediction).
  // estimate_yaw: also turn the scan about the body (PlanarCorrection); false and a map without
  // normals is the seed's translation-only ICP exactly. warm_start: the neighbours of the last
  // match (kept by the caller from scan to scan); consecutive scans see nearly the same places,
  // so an exact index starts its searches from them. The answers do not depend on it.
  MatchResult match(const WorldMap& map, const ScanPoints& scan, const Vec3& initial,
                    bool estimate_yaw = false, std::vector<Neighbour>* warm_start = nullptr) const;

 private:
  bool converged(const PlanarCorrection& step) const;
  // Step 1: find_nearest_points; while refining (and for the match's final pairs) without those
  // icp.refine_lines_only leaves out.
  Correspondences find_pairs(const WorldMap& map, const ScanPoints& moving,
                             std::vector<Neighbour>& nearest, bool refining) const;
  // One ICP step from the pairs: the correction to apply to the moving scan.
  PlanarCorrection step(const Correspondences& pairs, const Vec3& body, bool estimate_yaw,
                        const PlanarCorrection& so_far, double robust_scale) const;
  bool iterate(const WorldMap& map, const Vec3& initial, bool estimate_yaw, double robust_scale,
               int count, ScanPoints& moving, std::vector<Neighbour>& nearest,
               Correspondences& pairs, MatchResult& result) const;

  SlamConfig::Icp config_;
};

}  // namespace uavslam
