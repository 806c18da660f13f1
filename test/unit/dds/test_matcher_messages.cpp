// What the matcher publishes for a scan: the pose's quality, the keyframe, the status.
#include <gtest/gtest.h>

#include "dds/MatcherMessages.hpp"

namespace uavslam::dds {
namespace {

TEST(MatcherMessages, QualityFallsFromOneForAPerfectFitToTheLeastAtTheRejectionLimit) {
  SlamConfig config;  // icp.max_error_after 0.05 m^2
  ScanReport report;
  report.outcome = ScanOutcome::Accepted;
  report.error_after = 0.0;
  EXPECT_FLOAT_EQ(pose_quality(report, config), 1.0f);
  report.error_after = 0.025;
  EXPECT_FLOAT_EQ(pose_quality(report, config), 0.5f);
  report.error_after = 0.2;
  EXPECT_FLOAT_EQ(pose_quality(report, config), static_cast<float>(kLeastMatchQuality));
  report.outcome = ScanOutcome::ErrorIncreased;  // rejected, the pose carried by the prior
  report.error_after = 0.001;
  report.dead_reckoned = true;
  EXPECT_FLOAT_EQ(pose_quality(report, config), 0.0f) << "no scan confirmed it";
  report.outcome = ScanOutcome::MapInitialised;
  EXPECT_FLOAT_EQ(pose_quality(report, config), 1.0f) << "the scan that seeded the map";
}

TEST(MatcherMessages, TheKeyframeAndTheStatusCarryWhatTheScanGave) {
  Keyframe keyframe;
  keyframe.index = 4;
  keyframe.body.stamp = 12.5;
  keyframe.body.position = Vec3(1.0, 2.0, 0.2);
  keyframe.body.orientation = Eigen::AngleAxisd(0.4, Vec3::UnitZ());
  keyframe.sensor_origin = Vec3(1.0, 2.0, 0.3);
  keyframe.points = {Vec3(1.5, 2.0, 0.3), Vec3(1.0, 2.5, 0.3)};
  const msg::MapPoints points = keyframe_message(keyframe, {"map", "uav1"});
  EXPECT_EQ(points.keyframe_index(), 4u);
  EXPECT_EQ(points.header().seq(), 4u);
  EXPECT_EQ(points.header().vehicle_id(), "uav1");
  EXPECT_FLOAT_EQ(points.sensor_origin().z(), 0.3f);
  EXPECT_DOUBLE_EQ(points.body_position().z(), 0.2);
  EXPECT_NEAR(points.body_yaw(), 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(from_msg_time(points.header().stamp()), 12.5);
  ASSERT_EQ(from_msg(points).size(), 2u);
  EXPECT_TRUE(from_msg(points)[1].isApprox(Vec3(1.0, 2.5, 0.3), 1e-6));

  VehicleScan result;
  ScanReport& report = result.report;
  report.outcome = ScanOutcome::ErrorIncreased;
  report.iterations = 10;
  report.error_before = 0.01;
  report.error_after = 0.02;
  report.points_used = 216;
  report.map_size = 4320;
  report.seen.degenerate = 1;
  result.pipeline_seconds = 0.0004;
  result.tracking = {Tracking::Lost, TrackingReason::RepeatedRejections};
  Scan scan;
  scan.stamp = 12.5;
  scan.sequence = 99;
  MatcherCounts counts{100, 2, 3, 95, {}, 2};
  counts.loops.searches = 40;
  counts.loops.accepted = 9;
  const msg::MatcherStatus status = status_message(result, scan, 1.5, counts, 7, {"map", "uav1"});
  EXPECT_EQ(status.outcome(), "error_increased");
  EXPECT_EQ(status.scan_seq(), 99u);
  EXPECT_EQ(status.header().seq(), 7u);
  EXPECT_DOUBLE_EQ(from_msg_time(status.header().stamp()), 12.5);
  EXPECT_EQ(status.iterations(), 10);
  EXPECT_EQ(status.points_used(), 216u);
  EXPECT_EQ(status.map_size(), 4320u);
  EXPECT_DOUBLE_EQ(status.processing_ms(), 0.4);
  EXPECT_DOUBLE_EQ(status.latency_ms(), 1.5);
  EXPECT_EQ(status.scans_received(), 100u);
  EXPECT_EQ(status.scans_skipped(), 2u);
  EXPECT_EQ(status.scans_rejected(), 3u);
  EXPECT_EQ(status.scans_accepted(), 95u);
  EXPECT_EQ(status.tracking(), "lost");
  EXPECT_EQ(status.tracking_reason(), "repeated_rejections");
  EXPECT_EQ(status.degenerate_directions(), 1u);
  EXPECT_EQ(status.loops_searched(), 40u);
  EXPECT_EQ(status.loops_accepted(), 9u);
  EXPECT_EQ(status.corrections(), 2u);
  EXPECT_EQ(status.heading_drift_deg_per_min(), 0.0);  // none learnt
  VehicleScan drifting = result;
  drifting.heading_drift = 2.0 * M_PI / 180.0 / 60.0;  // rad/s
  EXPECT_NEAR(
      status_message(drifting, scan, 1.5, counts, 8, {"map", "uav1"}).heading_drift_deg_per_min(),
      2.0, 1e-12);
}

// The position's covariance as the pipeline reported it, the attitude's as the source states it;
// without a covariance (the seed's mode) the whole matrix says "unknown".
TEST(MatcherMessages, ThePoseCarriesTheCovariance) {
  SlamConfig config;
  config.imu.attitude_sigma = 0.02;
  config.imu.heading_sigma = 0.05;
  ScanReport report;
  report.outcome = ScanOutcome::Accepted;
  const auto unknown = pose_message(report, config, 1, 1, {"map", "uav1"});
  for (double c : unknown.covariance()) EXPECT_EQ(c, 0.0);

  report.covariance << 4.0, 0.1, 0.0,  //
      0.1, 1e-4, 0.0,                  //
      0.0, 0.0, 1e-4;
  const auto m = pose_message(report, config, 1, 1, {"map", "uav1"});
  EXPECT_DOUBLE_EQ(m.covariance()[0], 4.0);  // x: a corridor's axis
  EXPECT_DOUBLE_EQ(m.covariance()[1], 0.1);
  EXPECT_DOUBLE_EQ(m.covariance()[6], 0.1);
  EXPECT_DOUBLE_EQ(m.covariance()[7], 1e-4);
  EXPECT_DOUBLE_EQ(m.covariance()[14], 1e-4);
  EXPECT_DOUBLE_EQ(m.covariance()[21], 0.02 * 0.02);
  EXPECT_DOUBLE_EQ(m.covariance()[28], 0.02 * 0.02);
  EXPECT_DOUBLE_EQ(m.covariance()[35], 0.05 * 0.05);
  EXPECT_EQ(m.covariance()[3], 0.0) << "no cross-covariance between position and attitude";
}

TEST(MatcherMessages, KeyframePosesRoundTrip) {
  const std::vector<backend::NodePose> poses = {{Vec3(0.0, 0.0, 0.3), 0.0},
                                                {Vec3(1.5, -2.0, 1.2), -2.5}};
  const msg::KeyframePoses m =
      keyframe_poses_message(poses, {10.5, 20.75}, 30.25, 3, {"map", "uav1"});
  EXPECT_EQ(m.header().seq(), 3u);
  EXPECT_EQ(m.header().vehicle_id(), "uav1");
  EXPECT_DOUBLE_EQ(from_msg_time(m.header().stamp()), 30.25);
  const std::vector<KeyframePlacement> back = from_msg(m);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].index, 1u);
  EXPECT_DOUBLE_EQ(back[1].stamp, 20.75);
  EXPECT_EQ(back[1].pose.position, poses[1].position);
  EXPECT_EQ(back[1].pose.yaw, -2.5);
}

}  // namespace
}  // namespace uavslam::dds
