#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "SimTestHelpers.hpp"
#include "core/Angles.hpp"
#include "sim/Trajectory.hpp"

namespace uavslam::sim {
namespace {

// The heading of a level attitude.
double yaw_of(const Eigen::Quaterniond& q) {
  const Vec3 x_body = q * Vec3::UnitX();
  return std::atan2(x_body.y(), x_body.x());
}

// A tilted multirotor still heads along yaw: the horizontal heading vector is orthogonal to the
// body's y axis and on the body's forward side.
void expect_heading(const Eigen::Quaterniond& q, double yaw_deg) {
  const Vec3 heading(std::cos(deg_to_rad(yaw_deg)), std::sin(deg_to_rad(yaw_deg)), 0.0);
  EXPECT_NEAR((q * Vec3::UnitY()).dot(heading), 0.0, 1e-9);
  EXPECT_GT((q * Vec3::UnitX()).dot(heading), 0.9);
}

std::vector<Waypoint> square_flight() {
  return {{0.0, Vec3(1.0, 1.0, 0.3), 0.0},    {4.0, Vec3(1.0, 1.0, 1.5), 0.0},
          {9.0, Vec3(5.0, 1.0, 1.8), 30.0},   {14.0, Vec3(5.0, 5.0, 2.2), 120.0},
          {19.0, Vec3(1.0, 5.0, 1.2), 200.0}, {24.0, Vec3(1.0, 1.0, 0.3), 270.0}};
}

TEST(Trajectory, RejectsTooFewWaypoints) {
  EXPECT_THROW(Trajectory({{0.0, Vec3::Zero(), 0.0}}), std::invalid_argument);
}

TEST(Trajectory, RejectsTimesNotStrictlyIncreasing) {
  try {
    Trajectory({{0.0, Vec3::Zero(), 0.0}, {1.0, Vec3::Ones(), 0.0}, {1.0, Vec3::Zero(), 0.0}});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("strictly increasing"), std::string::npos) << e.what();
  }
}

TEST(Trajectory, PassesThroughEveryWaypoint) {
  const Trajectory trajectory(square_flight());
  for (const Waypoint& w : square_flight()) {
    const Pose pose = trajectory.pose_at(w.t);
    EXPECT_LT((pose.position - w.position).norm(), 1e-9) << "t = " << w.t;
    SCOPED_TRACE("t = " + std::to_string(w.t));
    expect_heading(pose.orientation, w.yaw_deg);
    EXPECT_DOUBLE_EQ(pose.stamp, w.t);
  }
}

TEST(Trajectory, RestsAtBothEndsAndClampsTime) {
  const Trajectory trajectory(square_flight());
  EXPECT_LT(trajectory.velocity_at(trajectory.start_time()).norm(), 1e-9);
  EXPECT_LT(trajectory.velocity_at(trajectory.end_time()).norm(), 1e-9);
  EXPECT_EQ(trajectory.pose_at(-5.0).position, trajectory.pose_at(0.0).position);
  EXPECT_EQ(trajectory.pose_at(99.0).position, trajectory.pose_at(24.0).position);
  EXPECT_DOUBLE_EQ(trajectory.pose_at(99.0).stamp, 24.0);
}

TEST(Trajectory, IsTwiceContinuouslyDifferentiableAtWaypoints) {
  const Trajectory trajectory(square_flight());
  constexpr double kStep = 1e-7;
  for (const double t : {4.0, 9.0, 14.0, 19.0}) {
    EXPECT_LT((trajectory.velocity_at(t - kStep) - trajectory.velocity_at(t + kStep)).norm(), 1e-5);
    EXPECT_LT(
        (trajectory.acceleration_at(t - kStep) - trajectory.acceleration_at(t + kStep)).norm(),
        1e-5);
  }
}

TEST(Trajectory, VelocityAndAccelerationAreTheDerivatives) {
  const Trajectory trajectory(square_flight());
  constexpr double kStep = 1e-5;
  for (const double t : {2.5, 7.3, 16.1}) {
    const Vec3 finite_velocity =
        (trajectory.pose_at(t + kStep).position - trajectory.pose_at(t - kStep).position) /
        (2 * kStep);
    const Vec3 finite_acceleration =
        (trajectory.velocity_at(t + kStep) - trajectory.velocity_at(t - kStep)) / (2 * kStep);
    EXPECT_LT((finite_velocity - trajectory.velocity_at(t)).norm(), 1e-6);
    EXPECT_LT((finite_acceleration - trajectory.acceleration_at(t)).norm(), 1e-6);
  }
}

TEST(Trajectory, HoverIsLevel) {
  const Trajectory trajectory(testing::hover(Vec3(1.0, 2.0, 1.5), 30.0, 10.0));
  const Pose pose = trajectory.pose_at(5.0);
  EXPECT_LT(((pose.orientation * Vec3::UnitZ()) - Vec3::UnitZ()).norm(), 1e-12);
  EXPECT_NEAR(yaw_of(pose.orientation), deg_to_rad(30.0), 1e-12);
  EXPECT_LT(trajectory.angular_velocity_at(5.0).norm(), 1e-9);
}

TEST(Trajectory, AcceleratingForwardPitchesTheNoseDown) {
  // From rest at x = 0 to rest at x = 4: accelerating in +x during the first half.
  const Trajectory trajectory({{0.0, Vec3(0.0, 0.0, 1.0), 0.0}, {4.0, Vec3(4.0, 0.0, 1.0), 0.0}});
  const double t = 0.5;
  const Vec3 acceleration = trajectory.acceleration_at(t);
  ASSERT_GT(acceleration.x(), 0.5);
  const Eigen::Quaterniond q = trajectory.pose_at(t).orientation;
  const Vec3 z_body = q * Vec3::UnitZ();
  const Vec3 x_body = q * Vec3::UnitX();
  EXPECT_GT(z_body.x(), 0.0);  // thrust tilts toward +x
  EXPECT_LT(x_body.z(), 0.0);  // nose down
  EXPECT_NEAR(std::atan2(z_body.x(), z_body.z()), std::atan2(acceleration.x(), kGravity), 1e-9);
  EXPECT_NEAR(z_body.y(), 0.0, 1e-12);  // no roll
}

TEST(Trajectory, AcceleratingLeftRollsLeft) {
  const Trajectory trajectory({{0.0, Vec3(0.0, 0.0, 1.0), 0.0}, {4.0, Vec3(0.0, 4.0, 1.0), 0.0}});
  const Vec3 z_body = trajectory.pose_at(0.5).orientation * Vec3::UnitZ();
  EXPECT_GT(z_body.y(), 0.0);
  EXPECT_NEAR(z_body.x(), 0.0, 1e-12);
}

TEST(Trajectory, YawTakesTheShortestTurn) {
  // 170 -> -170 degrees is a 20 degree turn through 180, not a 340 degree turn through 0.
  const Trajectory trajectory(
      {{0.0, Vec3(1.0, 1.0, 1.0), 170.0}, {10.0, Vec3(1.0, 1.0, 1.0), -170.0}});
  EXPECT_NEAR(std::abs(yaw_of(trajectory.pose_at(5.0).orientation)), kPi, 1e-9);
  EXPECT_NEAR(rad_to_deg(trajectory.yaw_at(10.0) - trajectory.yaw_at(0.0)), 20.0, 1e-9);
}

TEST(Trajectory, AngularVelocityOfAYawTurnIsTheYawRate) {
  const Trajectory trajectory({{0.0, Vec3(1.0, 1.0, 1.0), 0.0}, {10.0, Vec3(1.0, 1.0, 1.0), 90.0}});
  for (const double t : {2.0, 5.0, 8.0}) {
    constexpr double kStep = 1e-5;
    const double yaw_rate =
        (trajectory.yaw_at(t + kStep) - trajectory.yaw_at(t - kStep)) / (2 * kStep);
    const Vec3 omega = trajectory.angular_velocity_at(t);
    EXPECT_NEAR(omega.z(), yaw_rate, 1e-6);
    EXPECT_NEAR(omega.head<2>().norm(), 0.0, 1e-9);
  }
}

TEST(Trajectory, AngularVelocityIsInTheBodyFrame) {
  // Flying a curve: integrating the body rates over a short step reproduces the next attitude.
  const Trajectory trajectory(square_flight());
  constexpr double kStep = 1e-3;
  for (const double t : {6.0, 11.5, 16.7}) {
    const Vec3 omega = trajectory.angular_velocity_at(t + kStep / 2);
    const Eigen::Quaterniond predicted =
        trajectory.pose_at(t).orientation *
        Eigen::Quaterniond(Eigen::AngleAxisd(omega.norm() * kStep, omega.normalized()));
    EXPECT_LT(predicted.angularDistance(trajectory.pose_at(t + kStep).orientation), 1e-8);
  }
}

}  // namespace
}  // namespace uavslam::sim
