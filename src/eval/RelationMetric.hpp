// The Freiburg SLAM benchmark metric (Kümmerle et al., "On measuring the accuracy of SLAM
// algorithms", Autonomous Robots 27(4), 2009): an estimate is scored by how well it reproduces
// the true relative motions ("relations") between pairs of scans, not by absolute poses, so no
// alignment to a global frame is needed.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "eval/Relation.hpp"

namespace uavslam::eval {

// Mean, population standard deviation and largest value of the errors of one set of relations.
struct ErrorStatistics {
  std::size_t count = 0;
  double mean = 0.0;
  double std_dev = 0.0;
  double max = 0.0;
};

struct RelationSubsetErrors {
  std::size_t relations = 0;    // relations in the subset, matched or not
  std::size_t unmatched = 0;    // those whose t1 or t2 has no estimated pose
  ErrorStatistics translation;  // m
  ErrorStatistics rotation;     // rad
};

// One relation's errors; none when t1 or t2 has no estimated pose.
struct RelationError {
  double t1 = 0.0, t2 = 0.0;          // s, the relation's scans
  double length = 0.0;                // m, the relation's own translation
  std::optional<double> translation;  // m
  std::optional<double> rotation;     // rad
  // m: the estimated motion's translation less the relation's, both in t1's frame, along the
  // relation's direction (positive: the estimate moved farther) and across it (positive: to its
  // left). None for a relation under kMinDirectedLength, whose direction is noise.
  std::optional<double> along;
  std::optional<double> across;
};
inline constexpr double kMinDirectedLength = 0.01;  // m

struct RelationErrors {
  RelationSubsetErrors all;
  RelationSubsetErrors short_span;  // |t2 - t1| < short_span_limit: local accuracy
  double short_span_limit = 5.0;    // s, the split the benchmark's published figures use
  std::vector<RelationError> each;  // in the relations' order
};

// For each relation δ (true) the estimated motion is δ̂ = x̂(t1)⁻¹ ⊕ x̂(t2) and the error is
// e = δ⁻¹ ⊕ δ̂ (Kümmerle 2009, Eq. 1: δ̂ ⊖ δ); the translational error is |trans(e)| and the
// rotational error |rot(e)|, the angle normalised to [-π, π]. Estimated poses are looked up by
// timestamp value (the logs' stamps are not monotonic) within `stamp_tolerance` seconds;
// relations whose t1 or t2 has no estimate are counted as unmatched and left out of the figures.
RelationErrors compare_to_relations(const std::vector<PlanarStamped>& estimate,
                                    const std::vector<Relation>& relations,
                                    double stamp_tolerance = 1e-6);

// The same metric for motions estimated relation by relation (e.g. eval/ScanPairAlignment):
// estimated[i] is the estimate of relations[i], or nullopt (counted as unmatched).
RelationErrors compare_relation_estimates(const std::vector<Relation>& relations,
                                          const std::vector<std::optional<Relation>>& estimated);

// The relations' own consistency. Three relations joining the same three scans (a->b, b->c and
// a->c, each given in either direction) close to the identity when they are exact: the closure
// c = δ_ac⁻¹ ⊕ δ_ab ⊕ δ_bc measures how far the reference itself is from any one trajectory: no
// estimate can agree with all three relations of a triangle that does not close.
struct RelationClosures {
  std::size_t triangles = 0;
  ErrorStatistics translation;  // |trans(c)|, m
  ErrorStatistics rotation;     // |rot(c)|, rad
  // Those with a leg under short_span_limit (the subset that scores local accuracy).
  std::size_t triangles_with_short_leg = 0;
  ErrorStatistics short_leg_translation;
  double short_span_limit = 5.0;
};

// Scans are identified by their stamps (equal within `stamp_tolerance`).
RelationClosures relation_triangle_closures(const std::vector<Relation>& relations,
                                            double stamp_tolerance = 1e-6);

}  // namespace uavslam::eval
