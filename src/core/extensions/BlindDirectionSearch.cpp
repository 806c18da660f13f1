#include "core/extensions/BlindDirectionSearch.hpp"

#include <algorithm>
#include <cmath>

namespace uavslam {
namespace {

// A facing point's residual along its pair's wall normal, or none: no map point within
// max_distance, or one with no normal or a normal that does not agree with the scan's own (a jamb
// pairs with a jamb, not with the wall beside it).
std::optional<double> residual(const WorldMap& map, const Vec3& point, const Vec3& scan_normal,
                               const Neighbour& nearest, const BlindSearchOptions& options,
                               const MapPointFilter& usable) {
  if (usable && !usable(nearest.index)) return std::nullopt;
  const Vec3 r = point - map.point(nearest.index);
  if (r.squaredNorm() > options.max_distance * options.max_distance) return std::nullopt;
  if (map.normals().empty()) return std::nullopt;
  const Vec3& n = map.normals()[nearest.index];
  if (n.head<2>().dot(scan_normal.head<2>()) < options.normals_agree) return std::nullopt;
  return n.head<2>().dot(r.head<2>());
}

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// The points moved by `by`, and each one's nearest map point; a nearby shift's neighbours (the
// last step's) start the search.
Points shifted_and_paired(const WorldMap& map, const Points& points, const Vec3& by,
                          std::vector<Neighbour>& nearest) {
  Points moved = points;
  for (Vec3& p : moved) p += by;
  if (nearest.empty()) {
    map.find_nearest(moved, nearest);
  } else {
    map.find_nearest_again(moved, nearest);
  }
  return moved;
}

// Gauss-Newton on C along e from `offset`, the capped pairs left out: each step
// delta = -sum_i J_i r_i / sum_i J_i^2, J_i = n_i . e (the residual's change per metre along e).
std::optional<DirectionFix> refine(const WorldMap& map, const ScanPoints& scan, const Vec3& e,
                                   double offset, const BlindSearchOptions& options,
                                   const MapPointFilter& usable) {
  std::vector<Neighbour> nearest;
  double information = 0.0;
  std::vector<std::size_t> map_points;
  for (int iteration = 0; iteration < options.refine_iterations; ++iteration) {
    const Points moved = shifted_and_paired(map, scan.points, offset * e, nearest);
    double gradient = 0.0;
    information = 0.0;
    map_points.clear();
    for (std::size_t i = 0; i < moved.size(); ++i) {
      const std::optional<double> r =
          residual(map, moved[i], scan.normals[i], nearest[i], options, usable);
      if (!r || std::abs(*r) >= options.cap) continue;
      const double J = map.normals()[nearest[i].index].head<2>().dot(e.head<2>());
      gradient += J * *r;
      information += J * J;
      map_points.push_back(nearest[i].index);
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

}  // namespace

std::vector<double> cost_along(const WorldMap& map, const ScanPoints& scan, const Vec3& direction,
                               const std::vector<double>& shifts, const BlindSearchOptions& options,
                               const MapPointFilter& usable) {
  const double capped = options.cap * options.cap;
  std::vector<double> costs;
  costs.reserve(shifts.size());
  std::vector<Neighbour> nearest;
  for (const double s : shifts) {
    const Points moved = shifted_and_paired(map, scan.points, s * direction, nearest);
    double cost = 0.0;
    for (std::size_t i = 0; i < moved.size(); ++i) {
      const std::optional<double> r =
          residual(map, moved[i], scan.normals[i], nearest[i], options, usable);
      cost += r ? std::min(*r * *r, capped) : capped;
    }
    costs.push_back(cost);
  }
  return costs;
}

std::optional<DirectionFix> search_blind_direction(const WorldMap& map, const ScanPoints& scan,
                                                   const Vec3& direction,
                                                   const BlindSearchOptions& options,
                                                   const MapPointFilter& usable) {
  if (map.empty() || map.normals().empty() || options.step <= 0.0) return std::nullopt;
  // Only the points on surfaces that face along e can say where along e the scan lies; a wall
  // along e adds nothing but the jitter of the map points it pairs with as it slides.
  ScanPoints facing;
  for (std::size_t i = 0; i < scan.points.size() && i < scan.normals.size(); ++i) {
    if (std::abs(scan.normals[i].head<2>().dot(direction.head<2>())) < options.facing) continue;
    facing.points.push_back(scan.points[i]);
    facing.weights.push_back(scan.weights[i]);
    facing.normals.push_back(scan.normals[i]);
  }
  if (facing.points.size() < options.min_points) return std::nullopt;
  const int reach = static_cast<int>(std::ceil(options.half_width / options.step));
  if (reach < 2) return std::nullopt;
  std::vector<double> shifts;
  for (int k = -reach; k <= reach; ++k) shifts.push_back(k * options.step);
  const std::vector<double> costs = cost_along(map, facing, direction, shifts, options, usable);

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
      matched < std::max(double(options.min_points), 0.5 * double(facing.points.size()))) {
    return std::nullopt;
  }

  std::optional<DirectionFix> fix = refine(map, facing, direction, shifts[at], options, usable);
  // As many map points as scan points: two or three map points are a look-alike's chance.
  if (!fix || fix->map_points < options.min_points) return std::nullopt;
  fix->uniqueness = uniqueness;
  return fix;
}

}  // namespace uavslam
