// How far the scans themselves put a relation. Each relation's two scans are aligned to each other
// directly by the pipeline's own ICP (the config's metric, heading mode, gate and robust
// refinement), starting at the relation itself: the ICP moves only as far as the scans disagree
// with it. Scored against the relations like an estimate, this is a floor for any estimate made
// from these scans: where the scans' own best alignment lies centimetres from a relation, an
// estimate that followed the scans cannot agree with it either. A check of the reference, not of
// the SLAM.
#pragma once

#include "core/ScanOutcome.hpp"
#include "core/SlamConfig.hpp"
#include "core/Types.hpp"
#include "eval/Relation.hpp"

namespace uavslam::eval {

struct ScanPairAlignment {
  ScanOutcome outcome = ScanOutcome::NoCorrespondences;  // Accepted when the ICP accepted the pair
  Relation motion;  // the second scan's body in the frame of the first's (start: the relation)
  int iterations = 0;
};

// first, second: the scans at relation.t1 and relation.t2, each in its own body frame (the
// geometry's mount places the sensor on the body). The first scan becomes the map (every point
// config.map.subsample_every keeps, with normals for the point-to-line metric); the second is
// matched to it from the relation's motion.
ScanPairAlignment align_scan_pair(const Scan& first, const Scan& second, const Relation& relation,
                                  const SlamConfig& config);

}  // namespace uavslam::eval
