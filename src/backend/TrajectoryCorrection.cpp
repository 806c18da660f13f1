#include "backend/TrajectoryCorrection.hpp"

#include <algorithm>
#include <optional>

#include "backend/KeyframeGraph.hpp"
#include "core/Heading.hpp"

namespace uavslam::backend {
namespace {

// The frame of a stamp: how many corrections are stamped at or before it.
std::size_t frame_at(double stamp, const std::vector<StampedKeyframes>& corrections) {
  return static_cast<std::size_t>(
      std::upper_bound(corrections.begin(), corrections.end(), stamp,
                       [](double t, const StampedKeyframes& c) { return t < c.stamp; }) -
      corrections.begin());
}

// The pose in `poses` stamped exactly `stamp`, if there is one.
std::optional<Pose> pose_at(const std::vector<Pose>& poses, double stamp) {
  const auto it = std::lower_bound(poses.begin(), poses.end(), stamp,
                                   [](const Pose& p, double t) { return p.stamp < t; });
  if (it == poses.end() || it->stamp != stamp) return std::nullopt;
  return *it;
}

}  // namespace

std::vector<Pose> corrected_trajectory(const std::vector<Pose>& poses,
                                       const std::vector<StampedKeyframes>& corrections) {
  if (corrections.empty()) return poses;
  const std::vector<Pose>& final_keyframes = corrections.back().keyframes;
  std::vector<Pose> corrected = poses;
  for (Pose& p : corrected) {
    // The last keyframe at or before the pose, among those the last correction names.
    const auto after = std::upper_bound(final_keyframes.begin(), final_keyframes.end(), p.stamp,
                                        [](double t, const Pose& k) { return t < k.stamp; });
    if (after == final_keyframes.begin()) continue;
    const auto k = static_cast<std::size_t>(after - final_keyframes.begin()) - 1;
    const std::size_t frame = frame_at(p.stamp, corrections);
    const Pose& keyframe = final_keyframes[k];
    std::optional<Pose> in_frame;
    if (frame_at(keyframe.stamp, corrections) == frame) {
      in_frame = pose_at(poses, keyframe.stamp);
    } else if (frame > 0 && k < corrections[frame - 1].keyframes.size()) {
      in_frame = corrections[frame - 1].keyframes[k];
    }
    if (!in_frame) continue;
    const MapCorrection move = correction_between(node_of(*in_frame), node_of(keyframe));
    const NodePose moved = move(node_of(p));
    p.position = moved.position;
    p.orientation = yaw_rotation(move.yaw) * p.orientation;
  }
  return corrected;
}

}  // namespace uavslam::backend
