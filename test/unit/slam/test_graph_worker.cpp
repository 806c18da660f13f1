#include "slam/GraphWorker.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "unit/backend/HallFlight.hpp"

namespace uavslam {
namespace {

using backend::test::Flown;

// The hall's loop (backend/HallFlight.hpp) with a heading drift the front end states.
SlamConfig::LoopClosure hall_config() {
  SlamConfig::LoopClosure c;
  c.enabled = true;
  c.step_yaw_sigma = 0.005;
  c.step_yaw_sigma_per_radian = 0.0;
  return c;
}

std::vector<Flown> hall_flight() {
  return backend::test::drift(backend::test::loop_flight(), backend::test::hall(), 0.001);
}

// Inline, with a front end that takes every update at once and reports in its frame from then
// on: the final keyframe poses.
std::vector<backend::NodePose> inline_run(const std::vector<Flown>& flown) {
  GraphWorker worker(hall_config(), GraphWorker::Threading::Inline);
  backend::MapCorrection frame;
  std::size_t taken = 0;
  for (const Flown& f : flown) {
    Points points;
    for (const Vec3& p : f.points) points.push_back(frame.transform * p);
    worker.add({frame(f.pose), points, {}, taken, {}, Eigen::Matrix2d::Zero()});
    if (std::optional<GraphUpdate> u = worker.take()) {
      frame = frame.then(u->correction);
      taken = u->frame;
    }
  }
  worker.finish();
  return worker.poses();
}

// On its own thread, with a front end that never takes an update until the end: every keyframe
// arrives in the first frame and the worker brings it into the graph's. The graph is the same
// as inline, and the final update takes the front end from the first frame to the graph's.
TEST(GraphWorkerTest, AThreadThatIsNeverAskedGivesTheSameGraphAsInline) {
  const std::vector<Flown> flown = hall_flight();
  const std::vector<backend::NodePose> expected = inline_run(flown);
  GraphWorker worker(hall_config(), GraphWorker::Threading::Thread);
  for (const Flown& f : flown) worker.add({f.pose, f.points, {}, 0, {}, Eigen::Matrix2d::Zero()});
  worker.finish();
  EXPECT_GT(worker.counts().accepted, 0u);
  const std::vector<backend::NodePose> poses = worker.poses();
  ASSERT_EQ(poses.size(), expected.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    EXPECT_NEAR((poses[k].position - expected[k].position).norm(), 0.0, 1e-6) << k;
  }
  const std::optional<GraphUpdate> last = worker.take();
  ASSERT_TRUE(last.has_value());
  EXPECT_EQ(last->keyframes.size(), flown.size());
  // The newest keyframe as the front end had it, corrected, is where the graph has it.
  const backend::NodePose moved = last->correction(flown.back().pose);
  EXPECT_NEAR((moved.position - poses.back().position).norm(), 0.0, 1e-6);
  EXPECT_FALSE(worker.take().has_value()) << "an update is taken once";
}

// A keyframe that comes with heading turns (the front end learnt its source's drift): once it is
// in, every keyframe's heading turns by them, the steps with them, and the update says so.
TEST(GraphWorkerTest, HeadingTurnsMoveTheKeyframesAndTheUpdateSaysSo) {
  GraphWorker worker(hall_config(), GraphWorker::Threading::Inline);
  const std::vector<backend::NodePose> made{
      {Vec3(0.0, 0.0, 1.0), 0.0}, {Vec3(1.0, 0.0, 1.0), 0.0}, {Vec3(2.0, 0.0, 1.0), 0.0}};
  worker.add({made[0], {}, {}, 0, {}, Eigen::Matrix2d::Zero()});
  worker.add({made[1], {}, {}, 0, {}, Eigen::Matrix2d::Zero()});
  EXPECT_FALSE(worker.take().has_value());
  worker.add({made[2], {}, {}, 0, {0.0, 0.1, 0.2}, Eigen::Matrix2d::Zero()});
  const std::optional<GraphUpdate> update = worker.take();
  ASSERT_TRUE(update.has_value());
  EXPECT_EQ(update->headings_turned, 1u);
  ASSERT_EQ(update->poses.size(), 3u);
  EXPECT_NEAR(update->poses[1].yaw, 0.1, 1e-6);
  EXPECT_NEAR(update->poses[2].yaw, 0.2, 1e-6);
  // The second step, measured along x in the first keyframe's frame, turned with it.
  EXPECT_NEAR((update->poses[2].position - Vec3(1.0 + std::cos(0.1), std::sin(0.1), 1.0)).norm(),
              0.0, 1e-6);
  EXPECT_NEAR((update->correction(made[2]).position - update->poses[2].position).norm(), 0.0, 1e-6);

  // On the worker's own thread (slam_matcher) the same, once the worker has caught up.
  GraphWorker threaded(hall_config(), GraphWorker::Threading::Thread);
  threaded.add({made[0], {}, {}, 0, {}, Eigen::Matrix2d::Zero()});
  threaded.add({made[1], {}, {}, 0, {}, Eigen::Matrix2d::Zero()});
  threaded.add({made[2], {}, {}, 0, {0.0, 0.1, 0.2}, Eigen::Matrix2d::Zero()});
  threaded.finish();
  const std::optional<GraphUpdate> last = threaded.take();
  ASSERT_TRUE(last.has_value());
  EXPECT_EQ(last->headings_turned, 1u);
  ASSERT_EQ(last->poses.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR((last->poses[k].position - update->poses[k].position).norm(), 0.0, 1e-6) << k;
    EXPECT_NEAR(last->poses[k].yaw, update->poses[k].yaw, 1e-9) << k;
  }
}

TEST(GraphWorkerTest, FinishingWithoutKeyframesIsHarmless) {
  GraphWorker worker(hall_config(), GraphWorker::Threading::Thread);
  worker.finish();
  EXPECT_TRUE(worker.poses().empty());
  EXPECT_EQ(worker.counts().searches, 0u);
}

}  // namespace
}  // namespace uavslam
