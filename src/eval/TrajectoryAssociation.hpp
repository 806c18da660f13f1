// Pairs the poses of an estimated trajectory with ground-truth poses taken at the same time, the
// first step of every trajectory metric (as evo's sync.associate_trajectories).
#pragma once

#include <vector>

#include "core/Types.hpp"

namespace uavslam::eval {

struct PosePair {
  Pose estimate;
  Pose ground_truth;
};

// For each estimate pose, in stamp order, the ground-truth pose with the nearest stamp, if that is
// at most max_time_difference seconds away; estimates without one are left out. Either input may
// be unsorted. A ground-truth pose can pair with more than one estimate when the estimate is
// denser than max_time_difference allows to tell apart (evo does the same).
std::vector<PosePair> associate_by_stamp(const std::vector<Pose>& estimate,
                                         const std::vector<Pose>& ground_truth,
                                         double max_time_difference = 0.01);

}  // namespace uavslam::eval
