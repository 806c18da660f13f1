#include "core/ScanMatcher.hpp"

#include <algorithm>
#include <cmath>

namespace uavslam {

ScanPoints weigh_points(Points points, const std::vector<bool>& vertical, bool split_axes) {
  ScanPoints scan;
  scan.weights.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!split_axes) {
      scan.weights.emplace_back(1.0, 1.0, 1.0);
    } else {
      scan.weights.push_back(vertical[i] ? Vec3(0.0, 0.0, 1.0) : Vec3(1.0, 1.0, 0.0));
    }
  }
  scan.points = std::move(points);
  return scan;
}

Correspondences find_nearest_points(const WorldMap& map, const ScanPoints& scan,
                                    double max_distance) {
  std::vector<Neighbour> nearest;
  return find_nearest_points(map, scan, max_distance, nearest);
}

Correspondences find_nearest_points(const WorldMap& map, const ScanPoints& scan,
                                    double max_distance, std::vector<Neighbour>& nearest) {
  if (!nearest.empty()) {
    map.find_nearest_again(scan.points, nearest);
  } else {
    map.find_nearest(scan.points, nearest);
  }
  const double max_squared = max_distance * max_distance;
  const bool with_normals = !map.normals().empty();
  const bool with_scan_normals = !scan.normals.empty();
  Correspondences pairs;
  pairs.scan.reserve(scan.points.size());
  pairs.map.reserve(scan.points.size());
  pairs.map_index.reserve(scan.points.size());
  pairs.weights.reserve(scan.points.size());
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const Vec3& m = scan.points[i];
    const Vec3& d = map.point(nearest[i].index);
    const Vec3& w = scan.weights[i];
    if (max_distance > 0.0 && w.dot((m - d).cwiseAbs2()) > max_squared) continue;
    pairs.scan.push_back(m);
    pairs.map.push_back(d);
    pairs.map_index.push_back(nearest[i].index);
    pairs.weights.push_back(w);
    if (with_normals) pairs.normals.push_back(map.normals()[nearest[i].index]);
    if (with_scan_normals) pairs.scan_normals.push_back(scan.normals[i]);
  }
  return pairs;
}

void drop_pairs_without_normal(Correspondences& pairs) {
  if (pairs.normals.empty()) return;
  const bool with_scan_normals = !pairs.scan_normals.empty();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pairs.scan.size(); ++i) {
    Vec3 w = pairs.weights[i];
    if (pairs.normals[i].isZero()) w.head<2>().setZero();
    if (w.isZero()) continue;
    pairs.scan[kept] = pairs.scan[i];
    pairs.map[kept] = pairs.map[i];
    pairs.map_index[kept] = pairs.map_index[i];
    pairs.weights[kept] = w;
    pairs.normals[kept] = pairs.normals[i];
    if (with_scan_normals) pairs.scan_normals[kept] = pairs.scan_normals[i];
    ++kept;
  }
  pairs.scan.resize(kept);
  pairs.map.resize(kept);
  pairs.map_index.resize(kept);
  pairs.weights.resize(kept);
  pairs.normals.resize(kept);
  if (with_scan_normals) pairs.scan_normals.resize(kept);
}

Vec3 best_translation(const Correspondences& pairs) {
  Vec3 weighted_sum = Vec3::Zero();
  Vec3 weight_total = Vec3::Zero();
  for (std::size_t i = 0; i < pairs.scan.size(); ++i) {
    weighted_sum += pairs.weights[i].cwiseProduct(pairs.scan[i] - pairs.map[i]);
    weight_total += pairs.weights[i];
  }
  Vec3 t = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    if (weight_total[k] > 0.0) t[k] = weighted_sum[k] / weight_total[k];
  }
  return t;
}

double error_function(const Correspondences& pairs, const Vec3& t) {
  double sum = 0.0;
  for (std::size_t i = 0; i < pairs.scan.size(); ++i) {
    const Vec3 r = pairs.scan[i] - (pairs.map[i] + t);
    sum += pairs.weights[i].dot(counted_residual(pairs, i, r).cwiseAbs2());
  }
  return sum / double(pairs.scan.size());
}

void apply_transform(Points& points, const Vec3& correction) {
  for (Vec3& p : points) p += correction;
}

ScanMatcher::ScanMatcher(const SlamConfig::Icp& config) : config_(config) {}

// The seed runs its fixed count; beyond it (icp.stop_step > 0) the ICP stops once a step moves
// the scan less than stop_step (and turns it less than stop_step rad).
bool ScanMatcher::converged(const PlanarCorrection& step) const {
  return config_.stop_step > 0.0 && step.translation.norm() < config_.stop_step &&
         std::abs(step.yaw) < config_.stop_step;
}

PlanarCorrection ScanMatcher::step(const Correspondences& pairs, const Vec3& body,
                                   bool estimate_yaw, const PlanarCorrection& so_far,
                                   double robust_scale) const {
  if (estimate_yaw || !pairs.normals.empty()) {
    const CorrectionOptions options{estimate_yaw, config_.prior_weight, robust_scale};
    return best_correction(pairs, body, options, so_far);
  }
  PlanarCorrection seed;
  seed.translation = -best_translation(pairs);
  return seed;
}

Correspondences ScanMatcher::find_pairs(const WorldMap& map, const ScanPoints& moving,
                                        std::vector<Neighbour>& nearest, bool refining) const {
  Correspondences pairs =
      find_nearest_points(map, moving, config_.max_correspondence_distance, nearest);
  if (refining && config_.refine_lines_only) drop_pairs_without_normal(pairs);
  return pairs;
}

// Up to `count` iterations of find nearest points -> best correction -> apply, until a step is
// below stop_step; false when the correction grows beyond the seed's limits (result.outcome says
// which) or no pair is left.
bool ScanMatcher::iterate(const WorldMap& map, const Vec3& initial, bool estimate_yaw,
                          double robust_scale, int count, ScanPoints& moving,
                          std::vector<Neighbour>& nearest, Correspondences& pairs,
                          MatchResult& result) const {
  for (int k = 0; k < count; ++k) {
    if (result.iterations > 0) {
      pairs = find_pairs(map, moving, nearest, robust_scale > 0.0);
    }
    if (pairs.empty()) return false;
    const Vec3 body = initial + result.correction;
    const PlanarCorrection c =
        step(pairs, body, estimate_yaw, {result.yaw, result.correction}, robust_scale);
    if (c.yaw == 0.0) {
      apply_transform(moving.points, c.translation);
    } else {
      apply_correction(moving.points, body, c);
    }
    result.correction += c.translation;
    result.yaw += c.yaw;
    ++result.iterations;
    if (result.correction.norm() > config_.max_translation) {
      result.outcome = ScanOutcome::TranslationTooLarge;
      return false;
    }
    if (std::abs(result.yaw) > config_.max_rotation) {
      result.outcome = ScanOutcome::RotationTooLarge;
      return false;
    }
    if (converged(c)) break;
  }
  return true;
}

MatchResult ScanMatcher::match(const WorldMap& map, const ScanPoints& scan, const Vec3& initial,
                               bool estimate_yaw, std::vector<Neighbour>* warm_start) const {
  MatchResult result;
  result.position = initial;
  ScanPoints moving = scan;
  apply_transform(moving.points, initial);

  // Find initial error: the pairs found here also serve the first iteration.
  std::vector<Neighbour> own_nearest;
  std::vector<Neighbour>& nearest = warm_start ? *warm_start : own_nearest;
  Correspondences pairs = find_pairs(map, moving, nearest, false);
  if (pairs.empty()) return result;
  if (config_.refine_lines_only) {
    // The error before and after over the same kind of pairs (those the refinement keeps).
    Correspondences lines = pairs;
    drop_pairs_without_normal(lines);
    if (lines.empty()) return result;
    result.error_before = error_function(lines);
  } else {
    result.error_before = error_function(pairs);
  }

  // The ICP (every pair in the gate counts fully), then, with a robust scale, the refinement:
  // the converged scan settles on the pairs that agree with it (PlanarCorrection's Cauchy
  // kernel). The kernel only after convergence: during it, the far pairs are the pull of the
  // map's first visit that brings a returning vehicle back.
  if (!iterate(map, initial, estimate_yaw, 0.0, config_.iterations, moving, nearest, pairs,
               result)) {
    return result;
  }
  if (config_.robust_scale > 0.0 &&
      !iterate(map, initial, estimate_yaw, config_.robust_scale, config_.refine_iterations, moving,
               nearest, pairs, result)) {
    return result;
  }
  result.position = initial + result.correction;

  // Calculate resultant error.
  pairs = find_pairs(map, moving, nearest, true);
  if (pairs.empty()) return result;
  result.error_after = error_function(pairs);
  result.correspondences = pairs.scan.size();
  result.aligned = std::move(moving.points);
  result.pairs = std::move(pairs);
  if (result.error_after > config_.max_error_after) {
    result.outcome = ScanOutcome::ErrorTooLarge;
  } else if (result.error_after > config_.max_error_ratio * result.error_before) {
    result.outcome = ScanOutcome::ErrorIncreased;
  } else {
    result.outcome = ScanOutcome::Accepted;
  }
  return result;
}

}  // namespace uavslam
