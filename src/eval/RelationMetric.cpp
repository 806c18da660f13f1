#include "eval/RelationMetric.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <optional>
#include <utility>

#include "core/PlanarPose.hpp"

namespace uavslam::eval {
namespace {

// Estimated poses sorted by stamp, so that a stamp is found by value whatever the file order.
class PoseLookup {
 public:
  PoseLookup(std::vector<PlanarStamped> poses, double tolerance)
      : poses_(std::move(poses)), tolerance_(tolerance) {
    std::stable_sort(poses_.begin(), poses_.end(),
                     [](const PlanarStamped& a, const PlanarStamped& b) { return a.t < b.t; });
  }

  // The pose whose stamp is nearest to t, if it is within the tolerance.
  std::optional<PlanarPose> at(double t) const {
    const auto after =
        std::lower_bound(poses_.begin(), poses_.end(), t,
                         [](const PlanarStamped& pose, double stamp) { return pose.t < stamp; });
    const PlanarStamped* best = nullptr;
    if (after != poses_.end()) best = &*after;
    if (after != poses_.begin()) {
      const PlanarStamped& before = *std::prev(after);
      if (!best || t - before.t < best->t - t) best = &before;
    }
    if (!best || std::abs(best->t - t) > tolerance_) return std::nullopt;
    return PlanarPose{best->x, best->y, best->theta};
  }

 private:
  std::vector<PlanarStamped> poses_;
  double tolerance_;
};

ErrorStatistics statistics_of(const std::vector<double>& values) {
  ErrorStatistics s;
  s.count = values.size();
  if (values.empty()) return s;
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / static_cast<double>(values.size());
  double squares = 0.0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.std_dev = std::sqrt(squares / static_cast<double>(values.size()));
  s.max = *std::max_element(values.begin(), values.end());
  return s;
}

// Collects the errors of one subset of relations.
struct SubsetAccumulator {
  std::size_t relations = 0;
  std::size_t unmatched = 0;
  std::vector<double> translation;
  std::vector<double> rotation;

  RelationSubsetErrors result() const {
    return {relations, unmatched, statistics_of(translation), statistics_of(rotation)};
  }
};

// The relations as a graph: scan (its stamp in units of the tolerance) -> scan -> the motion.
using RelationGraph = std::map<long long, std::map<long long, PlanarPose>>;

RelationGraph graph_of(const std::vector<Relation>& relations, double stamp_tolerance) {
  const auto key = [&](double t) { return std::llround(t / stamp_tolerance); };
  RelationGraph graph;
  for (const Relation& r : relations) {
    const PlanarPose motion{r.x, r.y, r.yaw};
    graph[key(r.t1)][key(r.t2)] = motion;
    graph[key(r.t2)][key(r.t1)] = inverse(motion);
  }
  return graph;
}

}  // namespace

RelationErrors compare_to_relations(const std::vector<PlanarStamped>& estimate,
                                    const std::vector<Relation>& relations,
                                    double stamp_tolerance) {
  const PoseLookup lookup(estimate, stamp_tolerance);
  std::vector<std::optional<Relation>> estimated;
  estimated.reserve(relations.size());
  for (const Relation& relation : relations) {
    const std::optional<PlanarPose> from = lookup.at(relation.t1);
    const std::optional<PlanarPose> to = lookup.at(relation.t2);
    if (!from || !to) {
      estimated.emplace_back();
      continue;
    }
    const PlanarPose motion = motion_between(*from, *to);  // δ̂ = x̂(t1)⁻¹ ⊕ x̂(t2)
    estimated.push_back(Relation{relation.t1, relation.t2, motion.x, motion.y, motion.theta});
  }
  return compare_relation_estimates(relations, estimated);
}

RelationErrors compare_relation_estimates(const std::vector<Relation>& relations,
                                          const std::vector<std::optional<Relation>>& estimated) {
  RelationErrors errors;
  SubsetAccumulator all;
  SubsetAccumulator short_span;
  for (std::size_t i = 0; i < relations.size(); ++i) {
    const Relation& relation = relations[i];
    const bool is_short = std::abs(relation.t2 - relation.t1) < errors.short_span_limit;
    ++all.relations;
    if (is_short) ++short_span.relations;
    RelationError& each = errors.each.emplace_back();
    each.t1 = relation.t1;
    each.t2 = relation.t2;
    each.length = std::hypot(relation.x, relation.y);
    if (i >= estimated.size() || !estimated[i]) {
      ++all.unmatched;
      if (is_short) ++short_span.unmatched;
      continue;
    }
    const Relation& e = *estimated[i];
    const PlanarPose error =
        motion_between({relation.x, relation.y, relation.yaw}, {e.x, e.y, e.yaw});  // δ⁻¹ ⊕ δ̂
    const double translation = std::hypot(error.x, error.y);
    const double rotation = std::abs(error.theta);
    each.translation = translation;
    each.rotation = rotation;
    if (each.length >= kMinDirectedLength) {
      const double ux = relation.x / each.length;
      const double uy = relation.y / each.length;
      each.along = (e.x - relation.x) * ux + (e.y - relation.y) * uy;
      each.across = -(e.x - relation.x) * uy + (e.y - relation.y) * ux;
    }
    all.translation.push_back(translation);
    all.rotation.push_back(rotation);
    if (is_short) {
      short_span.translation.push_back(translation);
      short_span.rotation.push_back(rotation);
    }
  }
  errors.all = all.result();
  errors.short_span = short_span.result();
  return errors;
}

RelationClosures relation_triangle_closures(const std::vector<Relation>& relations,
                                            double stamp_tolerance) {
  const RelationGraph graph = graph_of(relations, stamp_tolerance);
  RelationClosures closures;
  const double short_keys = closures.short_span_limit / stamp_tolerance;
  std::vector<double> translation, rotation, short_leg;
  for (const auto& [a, from_a] : graph) {
    for (const auto& [b, ab] : from_a) {
      if (b <= a) continue;
      for (const auto& [c, bc] : graph.at(b)) {
        if (c <= b) continue;
        const auto ac = from_a.find(c);
        if (ac == from_a.end()) continue;
        const PlanarPose closure = motion_between(ac->second, compose(ab, bc));
        translation.push_back(std::hypot(closure.x, closure.y));
        rotation.push_back(std::abs(closure.theta));
        if (std::min({b - a, c - b}) < short_keys) short_leg.push_back(translation.back());
      }
    }
  }
  closures.triangles = translation.size();
  closures.translation = statistics_of(translation);
  closures.rotation = statistics_of(rotation);
  closures.triangles_with_short_leg = short_leg.size();
  closures.short_leg_translation = statistics_of(short_leg);
  return closures;
}

}  // namespace uavslam::eval
