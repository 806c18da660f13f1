#include <cmath>

#include <gtest/gtest.h>

#include "core/Angles.hpp"
#include "core/Heading.hpp"
#include "sim/Trajectory.hpp"
#include "sim/WheelOdometry.hpp"

namespace uavslam::sim {
namespace {

// A ground robot 8 m east, a quarter turn on the spot, 4 m north: its pose every 0.1 s.
std::vector<Pose> driven_path() {
  const Trajectory path({{0.0, Vec3(0.0, 0.0, 0.3), 0.0},
                         {16.0, Vec3(8.0, 0.0, 0.3), 0.0},
                         {21.0, Vec3(8.0, 0.0, 0.3), 90.0},
                         {29.0, Vec3(8.0, 4.0, 0.3), 90.0}},
                        Vehicle::ground);
  std::vector<Pose> poses;
  for (double t = 0.0; t <= 29.0 + 1e-9; t += 0.1) poses.push_back(path.pose_at(t));
  return poses;
}

double length(const std::vector<PlanarPose>& path) {
  double sum = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    sum += std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
  }
  return sum;
}

TEST(WheelOdometry, PerfectWheelsReadTheTruePath) {
  const std::vector<Pose> truth = driven_path();
  const std::vector<PlanarPose> odometry = wheel_odometry(truth, {0.0, 0.0, 0.0, 0.0, 0.0}, 1);
  ASSERT_EQ(odometry.size(), truth.size());
  for (std::size_t i = 0; i < truth.size(); i += 10) {
    const PlanarPose t = planar_pose(truth[i]);
    EXPECT_NEAR(odometry[i].x, t.x, 1e-3) << i;
    EXPECT_NEAR(odometry[i].y, t.y, 1e-3) << i;
    EXPECT_NEAR(wrap_angle(odometry[i].theta - t.theta), 0.0, 1e-6) << i;
  }
}

TEST(WheelOdometry, ScaleErrorsStretchTheDistanceAndTheTurn) {
  const std::vector<Pose> truth = driven_path();
  WheelOdometrySpec wheels{0.05, 0.1, 0.0, 0.0, 0.0};
  const std::vector<PlanarPose> odometry = wheel_odometry(truth, wheels, 1);
  std::vector<PlanarPose> true_path;
  for (const Pose& p : truth) true_path.push_back(planar_pose(p));
  EXPECT_NEAR(length(odometry) / length(true_path), 1.05, 1e-3);
  EXPECT_NEAR(odometry.back().theta, 1.1 * kPi / 2.0, 1e-3);  // 99 degrees for 90
}

TEST(WheelOdometry, NoiseGrowsWithTheMotionAndRepeatsWithTheSeed) {
  const std::vector<Pose> truth = driven_path();
  const WheelOdometrySpec noisy{0.0, 0.0, 0.02, 0.02, 0.01};
  const std::vector<PlanarPose> a = wheel_odometry(truth, noisy, 7);
  const std::vector<PlanarPose> b = wheel_odometry(truth, noisy, 7);
  const std::vector<PlanarPose> c = wheel_odometry(truth, noisy, 8);
  EXPECT_EQ(a.back().x, b.back().x);
  EXPECT_NE(a.back().x, c.back().x);
  // Standing still at the start (the spline's first instants barely move): no noise to speak of.
  EXPECT_NEAR(a[1].x, planar_pose(truth[1]).x, 1e-3);
  // 12 m driven: the end is off, by centimetres to decimetres.
  const PlanarPose end = planar_pose(truth.back());
  const double off = std::hypot(a.back().x - end.x, a.back().y - end.y);
  EXPECT_GT(off, 0.005);
  EXPECT_LT(off, 1.0);
}

TEST(Trajectory, AGroundRobotStaysLevelWhileItAccelerates) {
  const Trajectory path({{0.0, Vec3(0.0, 0.0, 0.3), 0.0}, {4.0, Vec3(3.0, 1.0, 0.3), 40.0}},
                        Vehicle::ground);
  const Trajectory flown({{0.0, Vec3(0.0, 0.0, 0.3), 0.0}, {4.0, Vec3(3.0, 1.0, 0.3), 40.0}});
  for (double t = 0.2; t < 4.0; t += 0.4) {
    EXPECT_NEAR(tilt_of(path.pose_at(t).orientation), 0.0, 1e-12) << t;
    EXPECT_NEAR(heading_of(path.pose_at(t).orientation), path.yaw_at(t), 1e-9) << t;
  }
  EXPECT_GT(tilt_of(flown.pose_at(0.2).orientation), 1e-3);  // a multirotor leans into it
}

}  // namespace
}  // namespace uavslam::sim
