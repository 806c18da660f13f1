#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "SimTestHelpers.hpp"
#include "core/Angles.hpp"
#include "core/ScanProjection.hpp"
#include "sim/LidarSimulator.hpp"
#include "sim/Trajectory.hpp"
#include "unit/sensor/ThreeBeamLidar.hpp"

namespace uavslam::sim {
namespace {

using test::three_beam_lidar;

Pose level_pose(const Vec3& position, double yaw_deg) {
  Pose pose;
  pose.position = position;
  pose.orientation = Eigen::AngleAxisd(deg_to_rad(yaw_deg), Vec3::UnitZ());
  return pose;
}

TEST(LidarSimulator, RangesAreTheDistancesToTheWallsFromTheSensor) {
  const World world(testing::empty_room());  // 10 x 8 x 3
  LidarSimulator lidar(three_beam_lidar(), world, 1);
  const Scan scan = lidar.scan_at(level_pose(Vec3(3.0, 5.0, 1.5), 0.0), 2.5, 7);
  EXPECT_DOUBLE_EQ(scan.stamp, 2.5);
  EXPECT_EQ(scan.sequence, 7u);
  EXPECT_EQ(scan.geometry, lidar.geometry());
  ASSERT_EQ(scan.ranges.size(), 3u);
  EXPECT_NEAR(scan.ranges[0], 5.0, 1e-5);  // right: the wall y = 0
  EXPECT_NEAR(scan.ranges[1], 7.0, 1e-5);  // ahead: the wall x = 10
  EXPECT_NEAR(scan.ranges[2], 3.0, 1e-5);  // left: the wall y = 8

  const Scan turned = lidar.scan_at(level_pose(Vec3(3.0, 5.0, 1.5), 90.0), 2.5, 8);
  EXPECT_NEAR(turned.ranges[1], 3.0, 1e-5);  // ahead is now +y
}

TEST(LidarSimulator, SensorSitsAtTheMountOffset) {
  LidarSpec spec = three_beam_lidar();
  spec.mount_position = Vec3(0.5, 0.0, 0.1);
  const World world(testing::empty_room());
  LidarSimulator lidar(spec, world, 1);
  EXPECT_NEAR(lidar.scan_at(level_pose(Vec3(3.0, 5.0, 1.5), 0.0), 0.0, 0).ranges[1], 6.5, 1e-5);
}

TEST(LidarSimulator, SurfacesBeyondMaxRangeReadInfinity) {
  LidarSpec spec = three_beam_lidar();
  spec.max_range = 4.0;
  const World world(testing::empty_room());
  LidarSimulator lidar(spec, world, 1);
  const Scan scan = lidar.scan_at(level_pose(Vec3(3.0, 5.0, 1.5), 0.0), 0.0, 0);
  EXPECT_EQ(scan.ranges[0], std::numeric_limits<float>::infinity());
  EXPECT_EQ(scan.ranges[1], std::numeric_limits<float>::infinity());
  EXPECT_NEAR(scan.ranges[2], 3.0, 1e-5);
}

TEST(LidarSimulator, FloorMirrorBeamsReadTheHeightOverTheFloor) {
  LidarSpec spec;
  spec.range_noise_std = 0.0;
  spec.floor_mirror.beams = 30;
  spec.floor_mirror.spread_deg = 20.0;
  const World world(testing::empty_room());
  LidarSimulator lidar(spec, world, 1);
  const double body_height = 1.5;
  const double sensor_height = body_height + spec.mount_position.z();
  const Scan scan = lidar.scan_at(level_pose(Vec3(5.0, 4.0, body_height), 40.0), 0.0, 0);
  for (int i = 0; i < 30; ++i) {
    const double tilt = deg_to_rad(-10.0 + 20.0 * i / 29.0);  // from the vertical
    EXPECT_NEAR(scan.ranges[static_cast<std::size_t>(i)], sensor_height / std::cos(tilt), 1e-5)
        << "beam " << i;
  }
}

// A vehicle turning on the spot while the scanner sweeps: each beam sees the room from the heading
// the vehicle had when it fired, the first at the stamp, the last sweep_seconds later; without a
// sweep every beam sees it from the stamp's.
TEST(LidarSimulator, EachBeamOfASweepIsFiredFromWhereTheVehicleWasThen) {
  const World world(testing::empty_room());
  const Trajectory turning({{0.0, Vec3(4.0, 3.0, 1.5), 0.0}, {2.0, Vec3(4.0, 3.0, 1.5), 90.0}});
  LidarSpec spec = test::three_beam_lidar();
  spec.sweep_seconds = 0.02;
  LidarSimulator sweeping(spec, world, 1);
  LidarSimulator instant(test::three_beam_lidar(), world, 1);
  const double taken = 1.0;  // mid-turn, about 1.2 rad/s
  const Scan swept = sweeping.scan_along(turning, taken, taken, 0);
  const Scan at_start = instant.scan_at(turning.pose_at(taken), taken, 0);
  const Scan at_end = instant.scan_at(turning.pose_at(taken + 0.02), taken, 0);
  ASSERT_EQ(swept.ranges.size(), 3u);
  EXPECT_FLOAT_EQ(swept.ranges[0], at_start.ranges[0]);
  EXPECT_FLOAT_EQ(swept.ranges[2], at_end.ranges[2]);
  EXPECT_GT(std::abs(swept.ranges[2] - at_start.ranges[2]), 0.01);
  const Scan unswept = instant.scan_along(turning, taken, taken, 0);
  EXPECT_FLOAT_EQ(unswept.ranges[2], at_start.ranges[2]);
}

// A UTM-30LX's 18.75 ms sweep from a vehicle turning at ~1.2 rad/s and flying at ~1.7 m/s,
// placed with the body's rate and velocity (core/ScanProjection's deskew), lies on the room's
// walls; placed from the stamp's pose alone, the sweep's far end misses them by centimetres.
TEST(LidarSimulator, ASweepPlacedWithTheBodysMotionLiesOnTheWalls) {
  const World world(testing::empty_room());
  const Trajectory flight({{0.0, Vec3(3.0, 3.0, 1.5), 0.0}, {2.0, Vec3(5.0, 4.0, 1.5), 90.0}});
  LidarSpec spec;
  spec.range_noise_std = 0.0;
  spec.sweep_seconds = 0.01875;
  LidarSimulator lidar(spec, world, 1);
  const double taken = 1.0;
  const Scan scan = lidar.scan_along(flight, taken, taken, 0);
  const Pose at_stamp = flight.pose_at(taken);
  const double middle = taken + spec.sweep_seconds / 2.0;
  const SweepMotion sweep{flight.angular_velocity_at(middle), flight.velocity_at(middle)};
  const auto farthest_off_the_walls = [&](const SweepMotion& motion) {
    double farthest = 0.0;
    for (const Vec3& p : project_scan(scan, at_stamp.orientation, motion).points) {
      farthest = std::max(farthest, world.distance_to_nearest_surface(p + at_stamp.position));
    }
    return farthest;
  };
  EXPECT_LT(farthest_off_the_walls(sweep), 0.002);
  EXPECT_GT(farthest_off_the_walls({}), 0.05);
}

TEST(LidarSimulator, RangeNoiseHasTheConfiguredSpread) {
  LidarSpec spec;  // range_noise_std 0.01
  LidarSpec exact = spec;
  exact.range_noise_std = 0.0;
  const World world(testing::empty_room());
  LidarSimulator noisy_lidar(spec, world, 3);
  LidarSimulator exact_lidar(exact, world, 3);
  const Pose pose = level_pose(Vec3(4.0, 3.0, 1.2), 15.0);
  const Scan truth = exact_lidar.scan_at(pose, 0.0, 0);
  double sum = 0.0, sum_squares = 0.0;
  int count = 0;
  for (int k = 0; k < 40; ++k) {
    const Scan scan = noisy_lidar.scan_at(pose, 0.0, 0);
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      const double error = double(scan.ranges[i]) - double(truth.ranges[i]);
      sum += error;
      sum_squares += error * error;
      ++count;
    }
  }
  const double mean = sum / count;
  const double std_dev = std::sqrt(sum_squares / count - mean * mean);
  EXPECT_NEAR(mean, 0.0, 3e-4);  // 43200 samples: the standard error is 5e-5
  EXPECT_NEAR(std_dev, 0.01, 0.0005);
}

TEST(LidarSimulator, SameSeedSameScansOtherSeedOtherNoise) {
  const World world(testing::empty_room());
  LidarSimulator first(LidarSpec{}, world, 5);
  LidarSimulator second(LidarSpec{}, world, 5);
  LidarSimulator other(LidarSpec{}, world, 6);
  const Pose pose = level_pose(Vec3(4.0, 3.0, 1.2), 15.0);
  const Scan a = first.scan_at(pose, 0.0, 0);
  EXPECT_EQ(a.ranges, second.scan_at(pose, 0.0, 0).ranges);
  EXPECT_NE(a.ranges, other.scan_at(pose, 0.0, 0).ranges);
  EXPECT_NE(a.ranges, first.scan_at(pose, 0.0, 0).ranges);  // the noise moves on
}

}  // namespace
}  // namespace uavslam::sim
