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

// With icp.heading_anchor the map is turned onto the orientation source's heading once the first
// scans have measured it: the keyframes made meanwhile wait for the back end and the scans for
// the dense products, and go in turned; a run that ends first puts them in as they are.
class SettlingHeading : public VehicleSlamInRoom {
 protected:
  static constexpr double kNoise = 0.5 * M_PI / 180.0;  // the first sample's, rad

  SettlingHeading() {
    config.nearest_neighbour.index = IndexKind::Exact;
    config.icp.motion_prior = MotionPrior::Odometry;
    config.icp.heading = HeadingMode::EveryScan;
    config.icp.metric = IcpMetric::PointToLine;
    config.icp.iterations = 20;
    config.icp.heading_anchor = 0.5;
    config.loop_closure.enabled = true;
  }

  // Scans 0.1 s apart, 0.3 m further along x each: a keyframe every second scan.
  std::vector<VehicleScan> fly_along(VehicleSlam& slam, int scans) {
    std::vector<VehicleScan> out;
    for (int k = 0; k < scans; ++k) {
      const double stamp = 0.1 * k;
      const Vec3 position = start + Vec3(0.3 * k, 0.0, 0.0);
      ImuSample imu = level_imu(stamp);
      imu.orientation = Eigen::AngleAxisd(k == 0 ? kNoise : 0.0, Vec3::UnitZ());
      slam.add_imu(imu);
      slam.add_odometry({stamp, position - start});
      out.push_back(slam.process_scan(room.scan_at(level_pose(position, stamp), stamp)));
      EXPECT_TRUE(out.back().posed()) << "scan " << k;
    }
    return out;
  }
};

TEST_F(SettlingHeading, KeyframesAndDenseScansGoInTurnedOnceTheHeadingSettles) {
  VehicleSlam slam(config, {0.0, std::nullopt});
  slam.start_at(start);
  const std::vector<VehicleScan> scans = fly_along(slam, 10);
  ASSERT_FALSE(scans[4].report.frame_turn);
  ASSERT_TRUE(scans[5].report.frame_turn) << "the first scan 0.5 s after the first";
  EXPECT_TRUE(scans[5].map_corrected) << "those who keep keyframes move them";
  EXPECT_EQ(slam.cloud()->points_added(), 10u * 1080u) << "the held scans went in with it";
  ASSERT_TRUE(slam.finish());
  ASSERT_GE(slam.keyframe_poses().size(), 4u);
  for (const backend::NodePose& keyframe : slam.keyframe_poses()) {
    EXPECT_LT(std::abs(keyframe.yaw), 0.002) << "the graph has the turned keyframes";
  }
}

TEST_F(SettlingHeading, ARunShorterThanTheWindowKeepsItsKeyframesAsTheyAre) {
  config.icp.heading_anchor = 5.0;
  VehicleSlam slam(config, {0.0, std::nullopt});
  slam.start_at(start);
  fly_along(slam, 4);
  EXPECT_EQ(slam.cloud()->points_added(), 0u) << "held while the heading may turn";
  ASSERT_TRUE(slam.finish());
  EXPECT_EQ(slam.cloud()->points_added(), 4u * 1080u);
  ASSERT_EQ(slam.keyframe_poses().size(), 2u);
  for (const backend::NodePose& keyframe : slam.keyframe_poses()) {
    EXPECT_NEAR(keyframe.yaw, kNoise, 0.002) << "the first sample's heading, never turned";
  }
}

}  // namespace
}  // namespace uavslam
