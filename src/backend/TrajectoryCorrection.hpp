// A pose stream corrected by the back end's keyframe corrections, as a receiver of `pose` and
// `keyframe_poses` sees them (the ground station): each pose moved with the keyframe it was made
// after, from where that keyframe was in the pose's map frame to where the last correction puts
// it.
//
// Frames: a correction stamped s (the first scan whose pose is in the corrected frame) starts a
// new frame, so a pose's frame is the number of corrections stamped at or before it. The keyframe
// a pose was made after is the last one stamped at or before it. Where that keyframe was in the
// pose's frame: the keyframe's own pose in the stream if it is in the same frame, else the pose
// the correction that started the pose's frame gave it.
#pragma once

#include <vector>

#include "core/Types.hpp"

namespace uavslam::backend {

struct StampedKeyframes {
  double stamp = 0.0;           // the first pose in the corrected frame
  std::vector<Pose> keyframes;  // every keyframe's scan stamp and pose, by index
};

// `poses` by stamp, `corrections` by stamp. A pose whose keyframe the last correction does not
// name (made after it) is in the final frame already and stays; so does one whose keyframe's
// pose in its frame is not known (its own pose lost on the way).
std::vector<Pose> corrected_trajectory(const std::vector<Pose>& poses,
                                       const std::vector<StampedKeyframes>& corrections);

}  // namespace uavslam::backend
