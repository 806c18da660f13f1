#include "slam/GraphWorker.hpp"

#include <gtest/gtest.h>

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
    worker.add({frame(f.pose), points, {}, taken});
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
  for (const Flown& f : flown) worker.add({f.pose, f.points, {}, 0});
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

TEST(GraphWorkerTest, FinishingWithoutKeyframesIsHarmless) {
  GraphWorker worker(hall_config(), GraphWorker::Threading::Thread);
  worker.finish();
  EXPECT_TRUE(worker.poses().empty());
  EXPECT_EQ(worker.counts().searches, 0u);
}

}  // namespace
}  // namespace uavslam
