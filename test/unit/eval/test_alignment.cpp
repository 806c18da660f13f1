#include <gtest/gtest.h>

#include "SampleTrajectories.hpp"
#include "eval/Alignment.hpp"

namespace uavslam::eval {
namespace {

Eigen::Isometry3d some_rigid_motion() {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = (Eigen::AngleAxisd(0.7, Vec3::UnitZ()) * Eigen::AngleAxisd(0.2, Vec3::UnitX()))
                        .toRotationMatrix();
  motion.translation() = Vec3(3.0, -1.0, 0.5);
  return motion;
}

std::vector<PosePair> paired(const std::vector<Pose>& estimate, const std::vector<Pose>& truth) {
  std::vector<PosePair> pairs;
  for (std::size_t i = 0; i < truth.size(); ++i) pairs.push_back({estimate[i], truth[i]});
  return pairs;
}

TEST(Alignment, NoneIsTheIdentity) {
  const std::vector<Pose> truth = test::circling_flight(50);
  const auto pairs = paired(test::moved(truth, some_rigid_motion()), truth);
  EXPECT_TRUE(estimate_alignment(pairs, Alignment::None).isApprox(Eigen::Isometry3d::Identity()));
}

TEST(Alignment, Se3UndoesARigidMotionOfTheEstimate) {
  const std::vector<Pose> truth = test::circling_flight(50);
  const Eigen::Isometry3d motion = some_rigid_motion();
  const auto pairs = paired(test::moved(truth, motion), truth);
  const Eigen::Isometry3d alignment = estimate_alignment(pairs, Alignment::SE3);
  EXPECT_TRUE((alignment * motion).isApprox(Eigen::Isometry3d::Identity(), 1e-9))
      << (alignment * motion).matrix();
}

TEST(Alignment, AlignEstimatesMovesPositionsAndOrientations) {
  const std::vector<Pose> truth = test::circling_flight(50);
  auto pairs = paired(test::moved(truth, some_rigid_motion()), truth);
  align_estimates(pairs, estimate_alignment(pairs, Alignment::SE3));
  for (const PosePair& pair : pairs) {
    EXPECT_LT((pair.estimate.position - pair.ground_truth.position).norm(), 1e-9);
    EXPECT_LT(pair.estimate.orientation.angularDistance(pair.ground_truth.orientation), 1e-9);
  }
}

}  // namespace
}  // namespace uavslam::eval
