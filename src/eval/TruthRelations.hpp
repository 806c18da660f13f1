// Relations in the manner of the Freiburg benchmark (Kümmerle et al. 2009) drawn from a known
// true path, for a simulated log (uavslam simulate --carmen): the scans along the path one step
// apart (moved step_length or turned step_turn since the last), each related to the next (the
// short, local relations), and revisits: a step's scan related to the first scan of an earlier
// visit to the same place (the long relations, which only a map that holds together scores well
// on).
#pragma once

#include <vector>

#include "eval/Relation.hpp"

namespace uavslam::eval {

struct TruthRelationOptions {
  double step_length = 0.2;       // m
  double step_turn = 0.17;        // rad (10 degrees)
  double revisit_after = 30.0;    // s between the two scans, at least
  double revisit_distance = 1.0;  // m apart, at most
  double revisit_turn = 0.8;      // rad of heading apart, at most
  int revisit_every = 10;         // steps: one revisit relation tried per this many
};

// `truth`: the true planar pose at every scan, in time order. The short relations first, then the
// revisits, each as the motion from t1's pose to t2's in t1's frame.
std::vector<Relation> relations_from_truth(const std::vector<PlanarStamped>& truth,
                                           const TruthRelationOptions& options = {});

}  // namespace uavslam::eval
