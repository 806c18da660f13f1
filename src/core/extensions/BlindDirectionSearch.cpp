#include "core/extensions/BlindDirectionSearch.hpp"

#include <algorithm>
#include <cmath>

namespace uavslam {
namespace {

// A beam facing e and the map points it may pair with over the whole window: those the caller
// allows, within `reach` (the farthest shift and max_distance) of it across the floor, their normal
// within 30 degrees of its own (a jamb pairs with a jamb, not with the wall beside it or its own
// back).
struct FacingBeam {
  Vec3 point;
  Vec3 normal;
  std::vector<std::size_t> candidates;
};

// Only the beams on surfaces that face along e can say where along e the scan lies; a wall along
// e adds nothing but the jitter of the map points it pairs with as it slides. Their candidates in
// one pass over the map.
std::vector<FacingBeam> facing_beams(const WorldMap& map, const ScanPoints& scan, const Vec3& e,
                                     double reach, const BlindSearchOptions& options,
                                     const MapPointFilter& usable) {
  std::vector<FacingBeam> beams;
  for (std::size_t i = 0; i < scan.points.size() && i < scan.normals.size(); ++i) {
    if (std::abs(scan.normals[i].head<2>().dot(e.head<2>())) < options.facing) continue;
    beams.push_back({scan.points[i], scan.normals[i], {}});
  }
  for (std::size_t m = 0; m < map.size(); ++m) {
    const Vec3& n = map.normals()[m];
    bool allowed = !usable;
    for (FacingBeam& beam : beams) {
      if (n.head<2>().dot(beam.normal.head<2>()) < options.normals_agree ||
          (map.point(m) - beam.point).head<2>().squaredNorm() > reach * reach) {
        continue;
      }
      if (!allowed && !usable(m)) break;
      allowed = true;
      beam.candidates.push_back(m);
    }
  }
  return beams;
}

struct Pair {
  std::size_t map_index = 0;
  double residual = 0.0;  // m, along the map point's normal
};

// The beam moved by `by`, paired with its nearest candidate within max_distance across the floor:
// a jamb's face stands over the storey, so its copy from a keyframe flown lower (the take-off's)
// still fixes a scan a metre higher, where a search in 3D finds it out of reach.
std::optional<Pair> pair_of(const WorldMap& map, const FacingBeam& beam, const Vec3& by,
                            double max_distance) {
  const Vec3 point = beam.point + by;
  std::optional<Pair> pair;
  double nearest = max_distance * max_distance;
  for (const std::size_t m : beam.candidates) {
    const Vec3 r = point - map.point(m);
    const double d2 = r.head<2>().squaredNorm();
    if (d2 > nearest) continue;
    nearest = d2;
    pair = Pair{m, map.normals()[m].head<2>().dot(r.head<2>())};
  }
  return pair;
}

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// Gauss-Newton on C along e from `offset`, the capped pairs left out: each step
// delta = -sum_i J_i r_i / sum_i J_i^2, J_i = n_i . e (the residual's change per metre along e).
std::optional<DirectionFix> refine(const WorldMap& map, const std::vector<FacingBeam>& beams,
                                   const Vec3& e, double offset,
                                   const BlindSearchOptions& options) {
  double information = 0.0;
  std::vector<std::size_t> map_points;
  for (int iteration = 0; iteration < options.refine_iterations; ++iteration) {
    double gradient = 0.0;
    information = 0.0;
    map_points.clear();
    for (const FacingBeam& beam : beams) {
      const std::optional<Pair> pair = pair_of(map, beam, offset * e, options.max_distance);
      if (!pair || std::abs(pair->residual) >= options.cap) continue;
      const double J = map.normals()[pair->map_index].head<2>().dot(e.head<2>());
      gradient += J * pair->residual;
      information += J * J;
      map_points.push_back(pair->map_index);
    }
    if (information <= 0.0) return std::nullopt;
    offset -= std::clamp(gradient / information, -options.step, options.step);
  }
  DirectionFix fix;
  fix.offset = offset;
  fix.information = information;
  std::sort(map_points.begin(), map_points.end());
  fix.map_points = static_cast<std::size_t>(std::unique(map_points.begin(), map_points.end()) -
                                            map_points.begin());
  return fix;
}

// C(s) at each shift (m along e).
std::vector<double> cost_along(const WorldMap& map, const std::vector<FacingBeam>& beams,
                               const Vec3& e, const std::vector<double>& shifts,
                               const BlindSearchOptions& options) {
  const double capped = options.cap * options.cap;
  std::vector<double> costs;
  costs.reserve(shifts.size());
  for (const double s : shifts) {
    double cost = 0.0;
    for (const FacingBeam& beam : beams) {
      const std::optional<Pair> pair = pair_of(map, beam, s * e, options.max_distance);
      cost += pair ? std::min(pair->residual * pair->residual, capped) : capped;
    }
    costs.push_back(cost);
  }
  return costs;
}

}  // namespace

std::optional<DirectionFix> search_blind_direction(const WorldMap& map, const ScanPoints& scan,
                                                   const Vec3& direction,
                                                   const BlindSearchOptions& options,
                                                   const MapPointFilter& usable) {
  if (map.empty() || map.normals().empty() || options.step <= 0.0) return std::nullopt;
  const int steps = static_cast<int>(std::ceil(options.half_width / options.step));
  if (steps < 2) return std::nullopt;
  std::vector<double> shifts;
  for (int k = -steps; k <= steps; ++k) shifts.push_back(k * options.step);
  const std::vector<FacingBeam> facing =
      facing_beams(map, scan, direction, shifts.back() + options.max_distance, options, usable);
  if (facing.size() < options.min_points) return std::nullopt;
  const std::vector<double> costs = cost_along(map, facing, direction, shifts, options);

  const auto best = std::min_element(costs.begin(), costs.end());
  const std::size_t at = static_cast<std::size_t>(best - costs.begin());
  // A dip at the window's edge may be the slope of one beyond it.
  if (at == 0 || at + 1 == costs.size()) return std::nullopt;
  const double background = median(costs);
  const double depth = background - *best;
  std::vector<double> deviations;
  double other = background;  // the lowest cost away from the best shift
  for (std::size_t k = 0; k < costs.size(); ++k) {
    if (std::abs(shifts[k] - shifts[at]) <= options.exclusion) continue;
    deviations.push_back(std::abs(costs[k] - background));
    other = std::min(other, costs[k]);
  }
  if (deviations.empty() || depth <= 0.0) return std::nullopt;
  // The jitter of a plain wall's C: the median absolute deviation, scaled to a sigma.
  const double jitter = std::max(1.4826 * median(deviations), 1e-12);
  const double contrast = depth / jitter;
  const double uniqueness = std::max(background - other, 0.0) / depth;
  // The dip must be several points fitting, not one.
  const double matched = depth / (options.cap * options.cap);
  if (contrast < options.contrast || uniqueness > options.uniqueness ||
      matched < std::max(double(options.min_points), 0.5 * double(facing.size()))) {
    return std::nullopt;
  }

  std::optional<DirectionFix> fix = refine(map, facing, direction, shifts[at], options);
  // As many map points as scan points: two or three map points are a look-alike's chance.
  if (!fix || fix->map_points < options.min_points) return std::nullopt;
  fix->uniqueness = uniqueness;
  return fix;
}

}  // namespace uavslam
