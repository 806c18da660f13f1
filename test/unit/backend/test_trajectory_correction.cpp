#include "backend/TrajectoryCorrection.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "backend/KeyframeGraph.hpp"
#include "core/Heading.hpp"

namespace uavslam::backend {
namespace {

// A front end flying a curve (poses 0..99, a keyframe every 10th) whose map the back end
// corrects twice, bending it: at pose 35 (the keyframes 0..3 moved, the front end's frame moved
// with keyframe 3) and at pose 72 (keyframes 0..7). Each pose is published in the frame its
// front end had; the corrected stream puts each where the final graph puts its keyframe, with
// the same offset from it as flown.
TEST(TrajectoryCorrectionTest, EachPoseFollowsItsKeyframeAcrossTheFrames) {
  std::vector<NodePose> flown;  // in the first frame
  for (int i = 0; i < 100; ++i) {
    flown.push_back({Vec3(0.1 * i, 0.002 * i * i, 1.0), 0.01 * i});
  }
  // The graph's keyframe poses after each correction: keyframe k bent by its own amount.
  const auto graph_pose = [&](int k, double amount) {
    NodePose n = flown[static_cast<std::size_t>(10 * k)];
    n.position += Vec3(-amount * k, amount * k * 0.5, 0.0);
    n.yaw += 0.2 * amount * k;
    return n;
  };
  const std::vector<std::pair<int, double>> plan = {{35, 0.05}, {72, 0.08}};
  std::vector<StampedKeyframes> corrections;
  std::vector<MapCorrection> frames = {MapCorrection{}};  // first frame -> each frame
  for (const auto& [at, amount] : plan) {
    StampedKeyframes c;
    c.stamp = at;
    const int newest = (at - 1) / 10;  // the keyframes made before the correction's scan
    for (int k = 0; k <= newest; ++k) c.keyframes.push_back(pose_of(graph_pose(k, amount), 10 * k));
    corrections.push_back(c);
    frames.push_back(correction_between(flown[static_cast<std::size_t>(10 * newest)],
                                        graph_pose(newest, amount)));
  }
  // Keyframes made after the last correction are in its frame as flown: the last correction's
  // list grows by them as a real front end's next one would.
  std::vector<Pose> published;
  for (int i = 0; i < 100; ++i) {
    std::size_t frame = 0;
    while (frame < plan.size() && i >= plan[frame].first) ++frame;
    published.push_back(pose_of(frames[frame](flown[static_cast<std::size_t>(i)]), i));
  }

  const std::vector<Pose> corrected = corrected_trajectory(published, corrections);
  ASSERT_EQ(corrected.size(), published.size());
  const std::vector<Pose>& final_keyframes = corrections.back().keyframes;
  for (int i = 0; i < 100; ++i) {
    const auto k = static_cast<std::size_t>(i / 10);
    if (k >= final_keyframes.size()) {
      // After the last keyframe the final correction names: already in the final frame.
      EXPECT_NEAR((corrected[i].position - published[i].position).norm(), 0.0, 1e-12) << i;
      continue;
    }
    const Constraint offset = relative(flown[10 * k], flown[static_cast<std::size_t>(i)]);
    const NodePose expected = compose(node_of(final_keyframes[k]), offset);
    EXPECT_NEAR((corrected[i].position - expected.position).norm(), 0.0, 1e-9) << i;
    EXPECT_NEAR(std::remainder(heading_of(corrected[i].orientation) - expected.yaw, 2 * M_PI), 0.0,
                1e-9)
        << i;
    EXPECT_EQ(corrected[i].stamp, published[i].stamp);
  }
}

TEST(TrajectoryCorrectionTest, WithoutCorrectionsTheStreamIsAsFlown) {
  const std::vector<Pose> poses = {pose_of({Vec3(1, 2, 3), 0.5}, 1.0)};
  const std::vector<Pose> same = corrected_trajectory(poses, {});
  ASSERT_EQ(same.size(), 1u);
  EXPECT_EQ(same[0].position, poses[0].position);
}

}  // namespace
}  // namespace uavslam::backend
