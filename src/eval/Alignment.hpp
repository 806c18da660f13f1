// Bringing an estimated trajectory into the ground-truth frame before comparing them: a SLAM run
// starts in its own frame, so only its shape can be judged unless the frames are known to agree.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "eval/TrajectoryAssociation.hpp"

namespace uavslam::eval {

enum class Alignment {
  None,  // the estimate is already in the ground-truth frame
  SE3,   // the rigid motion that best maps the estimate onto the ground truth (evo --align)
};

// The transform taking estimate-frame coordinates into the ground-truth frame: identity for None;
// for SE3 the least-squares rotation and translation of the paired positions (Umeyama 1991,
// without scale). SE3 needs at least 3 non-collinear positions to fix all of the rotation.
Eigen::Isometry3d estimate_alignment(const std::vector<PosePair>& pairs, Alignment alignment);

// Applies estimate_alignment's transform to the estimate side of every pair (position and
// orientation); the ground-truth side is left as it is.
void align_estimates(std::vector<PosePair>& pairs, const Eigen::Isometry3d& estimate_to_truth);

}  // namespace uavslam::eval
