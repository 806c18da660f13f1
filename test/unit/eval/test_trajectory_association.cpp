#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "SampleTrajectories.hpp"
#include "eval/TrajectoryAssociation.hpp"

namespace uavslam::eval {
namespace {

std::vector<Pose> shifted_in_time(std::vector<Pose> poses, double shift) {
  for (Pose& pose : poses) pose.stamp += shift;
  return poses;
}

TEST(TrajectoryAssociation, PairsEqualStamps) {
  const std::vector<Pose> truth = test::circling_flight(50);
  const std::vector<PosePair> pairs = associate_by_stamp(truth, truth);
  ASSERT_EQ(pairs.size(), truth.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    EXPECT_EQ(pairs[i].estimate.stamp, truth[i].stamp);
    EXPECT_EQ(pairs[i].ground_truth.stamp, truth[i].stamp);
  }
}

TEST(TrajectoryAssociation, PairsStampsShiftedWithinTheMaximum) {
  const std::vector<Pose> truth = test::circling_flight(50);
  const std::vector<PosePair> pairs = associate_by_stamp(shifted_in_time(truth, 0.005), truth);
  ASSERT_EQ(pairs.size(), truth.size());
  for (const PosePair& pair : pairs) {
    EXPECT_NEAR(pair.estimate.stamp - pair.ground_truth.stamp, 0.005, 1e-9);
  }
}

TEST(TrajectoryAssociation, LeavesOutStampsBeyondTheMaximum) {
  const std::vector<Pose> truth = test::circling_flight(50);
  EXPECT_TRUE(associate_by_stamp(shifted_in_time(truth, 0.02), truth).empty());
  EXPECT_EQ(associate_by_stamp(shifted_in_time(truth, 0.02), truth, 0.03).size(), truth.size());
}

TEST(TrajectoryAssociation, PicksTheNearestGroundTruthStamp) {
  const std::vector<Pose> truth = test::circling_flight(50);  // 0.1 s apart
  std::vector<Pose> estimate(1);
  estimate[0].stamp = truth[10].stamp + 0.06;  // nearer truth[11]
  const std::vector<PosePair> pairs = associate_by_stamp(estimate, truth, 0.05);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].ground_truth.stamp, truth[11].stamp);
}

TEST(TrajectoryAssociation, SortsUnsortedInputs) {
  const std::vector<Pose> truth = test::circling_flight(50);
  std::vector<Pose> shuffled_estimate = truth;
  std::vector<Pose> shuffled_truth = truth;
  std::mt19937 random(7);
  std::shuffle(shuffled_estimate.begin(), shuffled_estimate.end(), random);
  std::shuffle(shuffled_truth.begin(), shuffled_truth.end(), random);
  const std::vector<PosePair> pairs = associate_by_stamp(shuffled_estimate, shuffled_truth);
  ASSERT_EQ(pairs.size(), truth.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    EXPECT_EQ(pairs[i].estimate.stamp, truth[i].stamp);
    EXPECT_EQ(pairs[i].ground_truth.position, truth[i].position);
  }
}

TEST(TrajectoryAssociation, EmptyInputsGiveNoPairs) {
  const std::vector<Pose> truth = test::circling_flight(5);
  EXPECT_TRUE(associate_by_stamp({}, truth).empty());
  EXPECT_TRUE(associate_by_stamp(truth, {}).empty());
}

}  // namespace
}  // namespace uavslam::eval
