// One vehicle's SLAM around the core's pipeline: where the map starts, the odometry motion prior,
// the keyframes' sensor origin and the offline variant's dense products.
#include <gtest/gtest.h>

#include "slam/VehicleSlam.hpp"
#include "unit/core/SyntheticRoom.hpp"

namespace uavslam {
namespace {

using test::level_imu;

Pose level_pose(const Vec3& position, double stamp) {
  Pose p;
  p.stamp = stamp;
  p.position = position;
  return p;
}

class VehicleSlamInRoom : public ::testing::Test {
 protected:
  // Scans at start and then `jump` further along x: more than icp.max_translation (1 m) is beyond
  // what the seed's matcher may correct from the last position.
  std::vector<VehicleScan> fly(VehicleSlam& slam, double jump) {
    std::vector<VehicleScan> scans;
    const Vec3 positions[] = {start, start + Vec3(jump, 0.0, 0.0)};
    for (int k = 0; k < 2; ++k) {
      const double stamp = 0.1 * k;
      slam.add_imu(level_imu(stamp));
      slam.add_odometry({stamp, positions[k] - start});
      scans.push_back(slam.process_scan(room.scan_at(level_pose(positions[k], stamp), stamp)));
    }
    return scans;
  }

  test::SyntheticRoom room;
  SlamConfig config;
  Vec3 start{3.0, 3.0, 1.0};
};

TEST_F(VehicleSlamInRoom, TheFirstKeyframeIsSeenFromTheMountedSensorAtTheStart) {
  room.geometry->mount.translation() = Vec3(0.1, 0.0, 0.2);
  VehicleSlam slam(config);
  slam.start_at(start);
  slam.add_imu(level_imu(0.0));
  const VehicleScan first = slam.process_scan(room.scan_at(level_pose(start, 0.0), 0.0));
  EXPECT_EQ(first.report.outcome, ScanOutcome::MapInitialised);
  EXPECT_TRUE(first.report.pose.position.isApprox(start));
  ASSERT_TRUE(first.keyframe);
  EXPECT_EQ(first.keyframe->index, 0u);
  EXPECT_TRUE(first.keyframe->sensor_origin.isApprox(start + Vec3(0.1, 0.0, 0.2)));
  EXPECT_EQ(first.keyframe->points.size(), slam.pipeline().map().size());
  EXPECT_TRUE(first.report.added_points.empty()) << "moved into the keyframe";
  EXPECT_EQ(slam.keyframes(), 1u);
}

TEST_F(VehicleSlamInRoom, WithoutTheOdometryPriorAJumpBeyondTheLimitIsNotFound) {
  VehicleSlam slam(config);
  slam.start_at(start);
  EXPECT_EQ(slam.odometry_prior(), nullptr);
  const std::vector<VehicleScan> scans = fly(slam, 1.3);
  const bool found = scans[1].report.accepted() &&
                     (scans[1].report.pose.position - (start + Vec3(1.3, 0.0, 0.0))).norm() < 0.02;
  EXPECT_FALSE(found) << to_string(scans[1].report.outcome);
  EXPECT_FALSE(scans[1].report.dead_reckoned) << "no prior to dead-reckon with";
}

TEST_F(VehicleSlamInRoom, TheOdometryPriorStartsTheIcpWhereTheOdometrySays) {
  config.icp.motion_prior = MotionPrior::Odometry;
  VehicleSlam slam(config);
  slam.start_at(start);
  const std::vector<VehicleScan> scans = fly(slam, 1.3);
  EXPECT_EQ(scans[1].report.outcome, ScanOutcome::Accepted);
  EXPECT_LT((scans[1].report.pose.position - (start + Vec3(1.3, 0.0, 0.0))).norm(), 0.02);
  ASSERT_NE(slam.odometry_prior(), nullptr);
  EXPECT_EQ(slam.odometry_prior()->scans_with_prior(), 1u);
  EXPECT_EQ(slam.odometry_prior()->scans_without_prior(), 1u) << "the first scan has no last pose";
  EXPECT_TRUE(scans[1].keyframe) << "1.3 m of lateral motion is a keyframe";
  EXPECT_EQ(scans[1].keyframe->index, 1u);
}

TEST_F(VehicleSlamInRoom, DenseProductsOnlyWhenAskedFor) {
  config.icp.motion_prior = MotionPrior::Odometry;
  VehicleSlam realtime(config);
  realtime.start_at(start);
  fly(realtime, 0.6);
  EXPECT_EQ(realtime.cloud(), nullptr);
  EXPECT_EQ(realtime.occupancy(), nullptr);

  VehicleSlam offline(config, {0.05, OccupancyConfig{}});
  offline.start_at(start);
  fly(offline, 0.6);
  ASSERT_NE(offline.cloud(), nullptr);
  ASSERT_NE(offline.occupancy(), nullptr);
  EXPECT_EQ(offline.cloud()->points_added(), 2u * 1080u) << "every valid return of both scans";
  EXPECT_EQ(offline.occupancy()->keyframes_inserted(), offline.keyframes());
  EXPECT_EQ(offline.keyframes(), 2u);
  const std::unique_ptr<DenseCloud> cloud = offline.take_cloud();
  EXPECT_NE(cloud, nullptr);
  EXPECT_EQ(offline.cloud(), nullptr);
}

}  // namespace
}  // namespace uavslam
