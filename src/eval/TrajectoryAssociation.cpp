#include "eval/TrajectoryAssociation.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace uavslam::eval {
namespace {

std::vector<Pose> sorted_by_stamp(std::vector<Pose> poses) {
  std::stable_sort(poses.begin(), poses.end(),
                   [](const Pose& a, const Pose& b) { return a.stamp < b.stamp; });
  return poses;
}

// The pose of a stamp-sorted trajectory nearest in time to stamp: one of the two around it.
const Pose* nearest_in_time(const std::vector<Pose>& sorted, double stamp) {
  const auto after = std::lower_bound(sorted.begin(), sorted.end(), stamp,
                                      [](const Pose& pose, double t) { return pose.stamp < t; });
  if (after == sorted.begin()) return sorted.empty() ? nullptr : &*after;
  const auto before = std::prev(after);
  if (after == sorted.end()) return &*before;
  return (stamp - before->stamp <= after->stamp - stamp) ? &*before : &*after;
}

}  // namespace

std::vector<PosePair> associate_by_stamp(const std::vector<Pose>& estimate,
                                         const std::vector<Pose>& ground_truth,
                                         double max_time_difference) {
  const std::vector<Pose> sorted_ground_truth = sorted_by_stamp(ground_truth);
  std::vector<PosePair> pairs;
  for (const Pose& estimated : sorted_by_stamp(estimate)) {
    const Pose* truth = nearest_in_time(sorted_ground_truth, estimated.stamp);
    if (truth && std::abs(truth->stamp - estimated.stamp) <= max_time_difference) {
      pairs.push_back({estimated, *truth});
    }
  }
  return pairs;
}

}  // namespace uavslam::eval
