#include <cmath>
#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "SampleTrajectories.hpp"
#include "eval/TrajectoryMetrics.hpp"

namespace uavslam::eval {
namespace {

constexpr double kExact = 1e-9;  // what is zero up to rounding

MetricOptions aligned() {
  MetricOptions options;
  options.alignment = Alignment::SE3;
  return options;
}

// A position error growing linearly with time along x, as an odometry drift does.
std::vector<Pose> drifting(std::vector<Pose> poses, double metres_per_second) {
  const double start = poses.front().stamp;
  for (Pose& pose : poses) pose.position.x() += metres_per_second * (pose.stamp - start);
  return poses;
}

// A heading error growing linearly with time, applied in the world frame.
std::vector<Pose> yaw_drifting(std::vector<Pose> poses, double radians_per_second) {
  const double start = poses.front().stamp;
  for (Pose& pose : poses) {
    const double yaw = radians_per_second * (pose.stamp - start);
    pose.orientation = Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * pose.orientation;
  }
  return poses;
}

TEST(TrajectoryMetrics, IdenticalTrajectoriesHaveNoError) {
  const std::vector<Pose> truth = test::circling_flight();
  const TrajectoryErrors errors = compare_trajectories(truth, truth);
  EXPECT_EQ(errors.pairs, truth.size());
  EXPECT_NEAR(errors.ate_rmse, 0.0, kExact);
  EXPECT_NEAR(errors.ate_max, 0.0, kExact);
  EXPECT_NEAR(errors.rpe_translation_rmse, 0.0, kExact);
  EXPECT_NEAR(errors.rpe_rotation_rmse_deg, 0.0, 1e-6);
  EXPECT_NEAR(errors.final_position_error, 0.0, kExact);
}

TEST(TrajectoryMetrics, ConstantOffsetIsTheAteUnalignedAndVanishesAligned) {
  const std::vector<Pose> truth = test::circling_flight();
  const std::vector<Pose> estimate = test::offset(truth, Vec3(0.1, 0.0, 0.0));
  const TrajectoryErrors unaligned = compare_trajectories(estimate, truth);
  EXPECT_NEAR(unaligned.ate_rmse, 0.1, kExact);
  EXPECT_NEAR(unaligned.ate_mean, 0.1, kExact);
  EXPECT_NEAR(unaligned.ate_max, 0.1, kExact);
  EXPECT_NEAR(unaligned.final_position_error, 0.1, kExact);
  EXPECT_NEAR(compare_trajectories(estimate, truth, aligned()).ate_rmse, 0.0, 1e-9);
}

TEST(TrajectoryMetrics, RigidlyMovedTrajectoryHasNoErrorOnceAligned) {
  const std::vector<Pose> truth = test::circling_flight();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = Eigen::AngleAxisd(1.1, Vec3(0.2, 0.3, 1.0).normalized()).toRotationMatrix();
  motion.translation() = Vec3(5.0, -2.0, 0.3);
  const std::vector<Pose> estimate = test::moved(truth, motion);
  EXPECT_GT(compare_trajectories(estimate, truth).ate_rmse, 1.0);
  const TrajectoryErrors errors = compare_trajectories(estimate, truth, aligned());
  EXPECT_NEAR(errors.ate_rmse, 0.0, 1e-9);
  EXPECT_NEAR(errors.final_position_error, 0.0, 1e-9);
}

TEST(TrajectoryMetrics, SplitsTheAteIntoHorizontalAndVertical) {
  const std::vector<Pose> truth = test::circling_flight();
  const TrajectoryErrors vertical =
      compare_trajectories(test::offset(truth, Vec3(0.0, 0.0, 0.2)), truth);
  EXPECT_NEAR(vertical.ate_vertical_rmse, 0.2, kExact);
  EXPECT_NEAR(vertical.ate_horizontal_rmse, 0.0, kExact);
  const TrajectoryErrors both =
      compare_trajectories(test::offset(truth, Vec3(0.3, 0.4, 0.2)), truth);
  EXPECT_NEAR(both.ate_horizontal_rmse, 0.5, kExact);
  EXPECT_NEAR(both.ate_vertical_rmse, 0.2, kExact);
  EXPECT_NEAR(both.ate_rmse, std::hypot(0.5, 0.2), kExact);
}

TEST(TrajectoryMetrics, RpeOfAConstantOffsetIsZero) {
  const std::vector<Pose> truth = test::circling_flight();
  const TrajectoryErrors errors =
      compare_trajectories(test::offset(truth, Vec3(0.1, -0.2, 0.3)), truth);
  EXPECT_NEAR(errors.rpe_translation_rmse, 0.0, kExact);
  EXPECT_NEAR(errors.rpe_rotation_rmse_deg, 0.0, 1e-6);
}

TEST(TrajectoryMetrics, RpeOfADriftIsTheDriftOverDelta) {
  const std::vector<Pose> truth = test::circling_flight(200, 10.0);  // 19.9 s
  const std::vector<Pose> estimate = drifting(truth, 0.01);
  const TrajectoryErrors errors = compare_trajectories(estimate, truth);
  EXPECT_NEAR(errors.rpe_translation_rmse, 0.01, 1e-9);
  EXPECT_NEAR(errors.rpe_rotation_rmse_deg, 0.0, 1e-6);
  EXPECT_EQ(errors.rpe_delta, 1.0);
  EXPECT_EQ(errors.rpe_pairs, 190u);  // every pose with a pose 1 s later
  EXPECT_NEAR(errors.final_position_error, 0.01 * 19.9, 1e-9);

  MetricOptions two_seconds;
  two_seconds.rpe_delta = 2.0;
  EXPECT_NEAR(compare_trajectories(estimate, truth, two_seconds).rpe_translation_rmse, 0.02, 1e-9);
}

TEST(TrajectoryMetrics, RpePairsEachPoseWithThePoseClosestToDeltaLater) {
  std::vector<Pose> truth = test::circling_flight(3);
  truth[0].stamp = 0.0;
  truth[1].stamp = 0.999;  // 1 ms short of delta: closer than 2.0, the first pose >= delta later
  truth[2].stamp = 2.0;
  const TrajectoryErrors errors = compare_trajectories(drifting(truth, 0.01), truth);
  EXPECT_EQ(errors.rpe_pairs, 2u);  // (0, 1) and (1, 2), not (0, 2)
  EXPECT_NEAR(errors.rpe_translation_rmse, 0.01 * std::sqrt((0.999 * 0.999 + 1.001 * 1.001) / 2),
              1e-12);
}

TEST(TrajectoryMetrics, RpeRotationIsInDegrees) {
  const std::vector<Pose> truth = test::circling_flight();
  const double one_degree = EIGEN_PI / 180.0;
  const TrajectoryErrors errors = compare_trajectories(yaw_drifting(truth, one_degree), truth);
  EXPECT_NEAR(errors.rpe_rotation_rmse_deg, 1.0, 1e-6);
}

TEST(TrajectoryMetrics, RpeIsNanWhenNoPairSpansDelta) {
  const std::vector<Pose> truth = test::circling_flight(5, 10.0);  // 0.4 s
  const TrajectoryErrors errors = compare_trajectories(truth, truth);
  EXPECT_EQ(errors.rpe_pairs, 0u);
  EXPECT_TRUE(std::isnan(errors.rpe_translation_rmse));
  EXPECT_TRUE(std::isnan(errors.rpe_rotation_rmse_deg));
}

TEST(TrajectoryMetrics, AssociatesStampsOffByLessThanTheMaximum) {
  const std::vector<Pose> truth = test::circling_flight();
  std::vector<Pose> estimate = test::offset(truth, Vec3(0.1, 0.0, 0.0));
  for (Pose& pose : estimate) pose.stamp += 0.005;
  const TrajectoryErrors errors = compare_trajectories(estimate, truth);
  EXPECT_EQ(errors.pairs, truth.size());
  EXPECT_NEAR(errors.ate_rmse, 0.1, kExact);
}

TEST(TrajectoryMetrics, TooFewPairsThrowsNamingBothSides) {
  const std::vector<Pose> truth = test::circling_flight(50);
  std::vector<Pose> estimate = truth;
  for (Pose& pose : estimate) pose.stamp += 1000.0;
  try {
    compare_trajectories(estimate, truth);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_THAT(error.what(), testing::HasSubstr("only 0 estimate poses"));
    EXPECT_THAT(error.what(),
                testing::HasSubstr("estimate has 50 poses, stamps 1100.000 .. 1104.900 s"));
    EXPECT_THAT(error.what(),
                testing::HasSubstr("ground truth has 50 poses, stamps 100.000 .. 104.900 s"));
  }
  EXPECT_THROW(compare_trajectories({truth[0]}, truth), std::invalid_argument);
  EXPECT_THROW(compare_trajectories({}, {}), std::invalid_argument);
}

TEST(TrajectoryMetrics, RejectsANonPositiveRpeDelta) {
  const std::vector<Pose> truth = test::circling_flight(50);
  MetricOptions options;
  options.rpe_delta = 0.0;
  EXPECT_THROW(compare_trajectories(truth, truth, options), std::invalid_argument);
}

}  // namespace
}  // namespace uavslam::eval
