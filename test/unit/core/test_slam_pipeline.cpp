#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "SyntheticRoom.hpp"
#include "core/SlamPipeline.hpp"
#include "core/extensions/Relocalisation.hpp"

namespace uavslam {
namespace {

using test::level_imu;

class PipelineInRoom : public ::testing::Test {
 protected:
  test::SyntheticRoom room;
  SlamConfig config;
  Vec3 start{3.0, 3.0, 1.0};

  Pose pose_at(const Vec3& position, double stamp) const {
    Pose p;
    p.position = position;
    p.stamp = stamp;
    return p;
  }

  // Hovering at the start for `scans` scans at 40 Hz, each with a prior that agrees (no motion,
  // sure to 1 cm): the match noise's scales settle and the gate on the prior is armed. Returns
  // the next scan's stamp.
  double hover_to_settle(SlamPipeline& slam, int scans = 120) const {
    double t = 0.0;
    for (int k = 0; k < scans; ++k, t += 0.025) {
      slam.add_imu(level_imu(t));
      EXPECT_TRUE(slam.process_scan(room.scan_at(pose_at(start, t), t),
                                    {Vec3::Zero(), 1e-4 * Eigen::Matrix3d::Identity()})
                      .accepted());
    }
    return t;
  }
};

TEST_F(PipelineInRoom, FirstScanSeedsTheMapAtTheStart) {
  SlamPipeline slam(config, start);
  slam.add_imu(level_imu(0.0));
  const ScanReport r = slam.process_scan(room.scan_at(pose_at(start, 0.0), 0.0));
  EXPECT_EQ(r.outcome, ScanOutcome::MapInitialised);
  EXPECT_TRUE(r.map_updated);
  EXPECT_EQ(r.points_used, 216u);
  EXPECT_EQ(slam.map().size(), 216u);
  EXPECT_TRUE(r.pose.position.isApprox(start));
}

TEST_F(PipelineInRoom, DropsBadScansWithACountedReason) {
  SlamPipeline slam(config, start);
  Scan no_imu = room.scan_at(pose_at(start, 1.0), 1.0);
  EXPECT_EQ(slam.process_scan(no_imu).outcome, ScanOutcome::NoImu);

  slam.add_imu(level_imu(1.0));
  Scan no_geometry = no_imu;
  no_geometry.geometry.reset();
  EXPECT_EQ(slam.process_scan(no_geometry).outcome, ScanOutcome::Malformed);
  Scan short_ranges = no_imu;
  short_ranges.ranges.resize(10);
  EXPECT_EQ(slam.process_scan(short_ranges).outcome, ScanOutcome::Malformed);
  Scan bad_stamp = no_imu;
  bad_stamp.stamp = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(slam.process_scan(bad_stamp).outcome, ScanOutcome::Malformed);
  Scan empty = no_imu;
  empty.ranges.clear();
  EXPECT_EQ(slam.process_scan(empty).outcome, ScanOutcome::Malformed);
  Scan all_invalid = no_imu;
  std::fill(all_invalid.ranges.begin(), all_invalid.ranges.end(),
            std::numeric_limits<float>::infinity());
  const ScanReport r = slam.process_scan(all_invalid);
  EXPECT_EQ(r.outcome, ScanOutcome::TooFewPoints);
  EXPECT_EQ(r.invalid_ranges, 1080u);

  const auto& counts = slam.outcome_counts();
  EXPECT_EQ(counts[std::size_t(ScanOutcome::NoImu)], 1u);
  EXPECT_EQ(counts[std::size_t(ScanOutcome::Malformed)], 4u);
  EXPECT_EQ(counts[std::size_t(ScanOutcome::TooFewPoints)], 1u);
  EXPECT_TRUE(slam.map().empty());
}

TEST_F(PipelineInRoom, TracksAFlightAndAddsKeyframesAfterEnoughMotion) {
  config.nearest_neighbour.index = IndexKind::Exact;
  SlamPipeline slam(config, start);
  // 2 m along x at 0.5 m/s while climbing 0.5 m, scans at 40 Hz, IMU at 200 Hz. A level planar
  // scanner with no floor beams: only x-y is observable, so only x-y is checked.
  const auto truth_at = [&](double t) -> Vec3 { return start + Vec3(0.5 * t, 0.0, 0.125 * t); };
  std::size_t keyframes = 0;
  double squared_error_sum = 0.0;
  double max_error = 0.0;
  for (int k = 0; k <= 160; ++k) {
    const double t = k / 40.0;
    for (int i = 0; i < 5; ++i) slam.add_imu(level_imu(t + i / 200.0));
    const ScanReport r = slam.process_scan(room.scan_at(pose_at(truth_at(t), t), t));
    ASSERT_TRUE(r.accepted()) << "scan " << k << ": " << to_string(r.outcome);
    keyframes += r.map_updated;
    const double error = (r.pose.position - truth_at(t)).head<2>().norm();
    squared_error_sum += error * error;
    max_error = std::max(max_error, error);
    EXPECT_EQ(r.pose.position.z(), start.z()) << "no vertical beam, so the height must not move";
  }
  // Point-to-point pairs against a map of a few sparse keyframes leave centimetres of error (the
  // demo flight measures the real figure); a lost track would be metres off.
  EXPECT_LT(std::sqrt(squared_error_sum / 161.0), 0.06);
  EXPECT_LT(max_error, 0.15);
  // The first scan, then a keyframe per 0.5 m laterally.
  EXPECT_GE(keyframes, 4u);
  EXPECT_LE(keyframes, 5u);
  EXPECT_EQ(slam.map().size(), keyframes * 216u);
}

// A jump of 1.3 m between two scans: beyond the 0.3 m correspondence gate and beyond the seed's
// 1 m "distance moved" limit, so from the last position the matcher cannot find the scan.
TEST_F(PipelineInRoom, AMotionPriorStartsTheMatcherWhereTheVehicleWent) {
  config.nearest_neighbour.index = IndexKind::Exact;
  const Vec3 moved = start + Vec3(1.2, 0.5, 0.0);
  const auto run = [&](const Vec3& predicted_motion) {
    SlamPipeline slam(config, start);
    slam.add_imu(level_imu(0.0));
    slam.add_imu(level_imu(0.1));
    EXPECT_TRUE(slam.process_scan(room.scan_at(pose_at(start, 0.0), 0.0)).accepted());
    return slam.process_scan(room.scan_at(pose_at(moved, 0.1), 0.1),
                             MotionPrediction{predicted_motion, std::nullopt});
  };

  // The seed: no prior, the ICP starts from the last position and does not reach the scan.
  const ScanReport without = run(Vec3::Zero());
  EXPECT_FALSE(without.accepted() && (without.pose.position - moved).norm() < 0.05)
      << to_string(without.outcome);

  // A prediction 7 cm off (odometry is never exact): the matcher corrects the rest, and the 1 m
  // limit applies to that correction, not to the predicted motion.
  const ScanReport with = run(Vec3(1.15, 0.55, 0.0));
  ASSERT_TRUE(with.accepted()) << to_string(with.outcome);
  EXPECT_LT((with.pose.position - moved).head<2>().norm(), 0.02);
  EXPECT_EQ(with.pose.position.z(), start.z());
}

// The orientation source's heading goes wrong by 3 degrees after the first scan (a drifting gyro,
// wheel odometry after a slip) while the vehicle moves along x in the room. The seed trusts it;
// the rotation-aware modes measure the heading against the map and correct it.
class HeadingBias : public PipelineInRoom {
 protected:
  static constexpr double kBias = 3.0 * M_PI / 180.0;

  struct Run {
    std::vector<double> corrections;  // the pipeline's heading correction after each scan
    double last_position_error = 0.0;
    double last_heading_error = 0.0;
  };

  Run fly(const SlamConfig& c, int scans) const {
    SlamPipeline slam(c, start);
    Run run;
    for (int k = 0; k < scans; ++k) {
      const double t = k * 0.1;
      const Vec3 truth = start + Vec3(0.05 * k, 0.0, 0.0);
      ImuSample imu = level_imu(t);
      imu.orientation = Eigen::AngleAxisd(k == 0 ? 0.0 : kBias, Vec3::UnitZ());
      slam.add_imu(imu);
      const ScanReport r =
          slam.process_scan(room.scan_at(pose_at(truth, t), t),
                            {k == 0 ? Vec3::Zero() : Vec3(0.05, 0, 0), std::nullopt});
      EXPECT_TRUE(r.accepted() || r.dead_reckoned) << "scan " << k << ": " << to_string(r.outcome);
      run.corrections.push_back(slam.heading_correction());
      run.last_position_error = (r.pose.position - truth).head<2>().norm();
      const Vec3 forward = r.pose.orientation * Vec3::UnitX();
      run.last_heading_error = std::abs(std::atan2(forward.y(), forward.x()));
    }
    return run;
  }

  SlamConfig rotation_aware(HeadingMode heading, IcpMetric metric) const {
    SlamConfig c = config;
    c.nearest_neighbour.index = IndexKind::Exact;
    c.icp.motion_prior = MotionPrior::Odometry;
    c.icp.heading = heading;
    c.icp.metric = metric;
    c.icp.iterations = 20;
    c.icp.heading_check_every = 5;
    return c;
  }
};

TEST_F(HeadingBias, TheSeedKeepsTheSourcesHeading) {
  SlamConfig c = config;
  c.nearest_neighbour.index = IndexKind::Exact;
  const Run run = fly(c, 10);
  for (const double correction : run.corrections) EXPECT_EQ(correction, 0.0);
  EXPECT_NEAR(run.last_heading_error, kBias, 1e-9);
}

TEST_F(HeadingBias, EveryScanMeasuresTheHeadingAndUndoesTheBias) {
  for (const IcpMetric mode : {IcpMetric::PointToPoint, IcpMetric::PointToLine}) {
    const std::string_view metric = mode_name(mode);
    const Run run = fly(rotation_aware(HeadingMode::EveryScan, mode), 10);
    EXPECT_NEAR(run.corrections[1], -kBias, 0.002) << metric << ": corrected at the first scan";
    EXPECT_LT(run.last_heading_error, 0.002) << metric;
    EXPECT_LT(run.last_position_error, 0.01) << metric;
  }
}

TEST_F(HeadingBias, APeriodicCheckCorrectsTheHeadingOnlyWhenItIsDue) {
  const Run run = fly(rotation_aware(HeadingMode::PeriodicCheck, IcpMetric::PointToLine), 12);
  // Scans 1-4 are matched translation-only with the biased heading; scan 5 is the first check.
  for (int k = 1; k <= 4; ++k) EXPECT_EQ(run.corrections[std::size_t(k)], 0.0) << "scan " << k;
  EXPECT_NEAR(run.corrections[5], -kBias, 0.002);
  // The next check (scan 10) finds the heading within tolerance and leaves it as it was.
  EXPECT_EQ(run.corrections[10], run.corrections[9]);
  EXPECT_LT(run.last_heading_error, 0.002);
  EXPECT_LT(run.last_position_error, 0.01);
}

// The first orientation sample is 0.5 degree off (one sample's noise), the later ones right. With
// the heading estimated in every scan the map keeps the first sample's heading; anchored, it is
// turned onto the source's once the window's scans have measured how far off it is.
TEST_F(HeadingBias, TheHeadingAnchorTurnsTheMapOntoTheSourcesHeading) {
  const double noise = 0.5 * M_PI / 180.0;
  for (const double window : {0.0, 0.5}) {
    SlamConfig c = rotation_aware(HeadingMode::EveryScan, IcpMetric::PointToLine);
    c.icp.heading_anchor = window;
    SlamPipeline slam(c, start);
    std::optional<FrameTurn> turned;
    std::size_t turns = 0;
    double heading_error = 0.0;
    double position_error = 0.0;
    for (int k = 0; k < 10; ++k) {
      const double t = k * 0.1;
      const Vec3 truth = start + Vec3(0.05 * k, 0.0, 0.0);
      ImuSample imu = level_imu(t);
      imu.orientation = Eigen::AngleAxisd(k == 0 ? noise : 0.0, Vec3::UnitZ());
      slam.add_imu(imu);
      const ScanReport r =
          slam.process_scan(room.scan_at(pose_at(truth, t), t),
                            {k == 0 ? Vec3::Zero() : Vec3(0.05, 0, 0), std::nullopt});
      ASSERT_TRUE(r.accepted()) << "scan " << k << ": " << to_string(r.outcome);
      if (r.frame_turn) {
        turned = r.frame_turn;
        ++turns;
        EXPECT_NEAR(t, window, 1e-9) << "turned at the first scan past the window";
      }
      heading_error = heading_of(r.pose.orientation);
      position_error = (r.pose.position - truth).head<2>().norm();
    }
    if (window == 0.0) {
      EXPECT_FALSE(turned);
      EXPECT_NEAR(heading_error, noise, 0.002) << "the first sample's heading, kept";
      continue;
    }
    ASSERT_TRUE(turned);
    EXPECT_EQ(turns, 1u);
    EXPECT_TRUE(turned->origin.isApprox(start)) << "about the take-off point";
    EXPECT_NEAR(turned->yaw, -noise, 0.002);
    EXPECT_LT(std::abs(heading_error), 0.002);
    EXPECT_LT(position_error, 0.01);
    EXPECT_TRUE(slam.frame_settled());
  }
}

// Rolled by 15 degrees the scanner still sees the room's walls (they are vertical), but a tilted
// cut of a room with furniture is not the map's: with heading_max_tilt 10 degrees the heading
// stays the source's, biased; without a limit the scan measures it.
TEST_F(HeadingBias, ATiltedScannerLeavesTheHeadingToTheSource) {
  const Eigen::Quaterniond roll(Eigen::AngleAxisd(15.0 * M_PI / 180.0, Vec3::UnitX()));
  for (const double max_tilt : {0.0, 10.0 * M_PI / 180.0}) {
    SlamConfig c = rotation_aware(HeadingMode::EveryScan, IcpMetric::PointToLine);
    c.icp.heading_max_tilt = max_tilt;
    SlamPipeline slam(c, start);
    for (int k = 0; k < 4; ++k) {
      const double t = k * 0.1;
      Pose truth = pose_at(start + Vec3(0.05 * k, 0.0, 0.0), t);
      truth.orientation = roll;
      ImuSample imu = level_imu(t);
      imu.orientation = Eigen::AngleAxisd(k == 0 ? 0.0 : kBias, Vec3::UnitZ()) * roll;
      slam.add_imu(imu);
      const ScanReport r = slam.process_scan(
          room.scan_at(truth, t), {k == 0 ? Vec3::Zero() : Vec3(0.05, 0, 0), std::nullopt});
      ASSERT_TRUE(r.accepted()) << "scan " << k << ": " << to_string(r.outcome);
    }
    if (max_tilt == 0.0) {
      EXPECT_NEAR(slam.heading_correction(), -kBias, 0.002) << "measured";
    } else {
      EXPECT_EQ(slam.heading_correction(), 0.0) << "left to the source";
    }
  }
}

// The back end moved the map (a turn and a shift of the whole frame, as an optimised pose graph
// does about the newest keyframe): the pipeline's map is the moved one, the vehicle moves with
// it, and the next scans, turned by the same heading, are matched in the moved frame just as an
// unmoved pipeline matches them in the old one.
TEST_F(PipelineInRoom, AReplacedMapMovesTheVehicleAndTheHeadingWithIt) {
  config.nearest_neighbour.index = IndexKind::Exact;
  SlamPipeline slam(config, start);
  SlamPipeline unmoved(config, start);
  for (SlamPipeline* p : {&slam, &unmoved}) {
    p->add_imu(level_imu(0.0));
    ASSERT_TRUE(p->process_scan(room.scan_at(pose_at(start, 0.0), 0.0)).map_updated);
  }

  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.linear() = Eigen::AngleAxisd(0.05, Vec3::UnitZ()).toRotationMatrix();
  moved.translation() = Vec3(0.3, -0.2, 0.0);
  MapKeyframe keyframe;
  keyframe.position = moved * start;
  for (const Vec3& p : slam.map().points()) keyframe.points.push_back(moved * p);
  EXPECT_THROW(slam.replace_map({keyframe, keyframe}, moved, 0.05), std::invalid_argument);
  slam.replace_map({keyframe}, moved, 0.05);

  EXPECT_NEAR((slam.pose().position - moved * start).norm(), 0.0, 1e-9);
  EXPECT_NEAR(slam.heading_correction(), 0.05, 1e-12);
  ASSERT_EQ(slam.map().size(), keyframe.points.size());
  EXPECT_NEAR((slam.map().point(7) - keyframe.points[7]).norm(), 0.0, 1e-12);
  for (int k = 1; k <= 40; ++k) {
    const double t = k / 40.0;
    const Vec3 truth = start + Vec3(0.02 * k, 0.01 * k, 0.0);
    ScanReport r[2];
    int i = 0;
    for (SlamPipeline* p : {&slam, &unmoved}) {
      p->add_imu(level_imu(t));
      r[i++] = p->process_scan(room.scan_at(pose_at(truth, t), t));
    }
    ASSERT_TRUE(r[0].accepted()) << k;
    EXPECT_EQ(r[0].map_updated, r[1].map_updated) << k;
    EXPECT_LT((r[0].pose.position - moved * r[1].pose.position).norm(), 0.002) << k;
  }
}

// A failed match with a motion prior leaves the vehicle where the prediction says, not where it
// was: a rejected scan is dead-reckoned.
// Beyond the seed (scan.deskew): how the body moved over a scanner's sweep, as the scan was placed:
// the gyro's rate at mid-sweep and the prior's mean velocity since the last pose. A scan stamped
// closer to the last pose than its sweep lasts (a log's jittering stamps) keeps the turn only:
// 1 cm of the prior's noise over 1 ms would read as 10 m/s. The seed places every beam at the
// stamp.
TEST_F(PipelineInRoom, TheSweepIsPlacedByTheGyrosRateAndThePriorsVelocity) {
  room.geometry->sweep_beams_in_order(0.01875 / 1079.0);
  const auto turning_imu = [](double stamp) {
    ImuSample sample = level_imu(stamp);
    sample.angular_velocity = Vec3(0.0, 0.0, 0.5);
    return sample;
  };
  const Vec3 moved(0.02, -0.01, 0.0);
  const MotionPrediction prior{moved, 1e-4 * Eigen::Matrix3d::Identity()};
  for (const bool deskew : {true, false}) {
    config.scan.deskew = deskew;
    SlamPipeline slam(config, start);
    for (const double t : {0.0, 0.025, 0.035}) slam.add_imu(turning_imu(t));
    ASSERT_TRUE(slam.process_scan(room.scan_at(pose_at(start, 0.0), 0.0)).accepted());
    const ScanReport r =
        slam.process_scan(room.scan_at(pose_at(start + moved, 0.025), 0.025), prior);
    ASSERT_TRUE(r.accepted());
    const ScanReport soon =
        slam.process_scan(room.scan_at(pose_at(start + 2.0 * moved, 0.035), 0.035), prior);
    ASSERT_TRUE(soon.accepted());
    if (!deskew) {
      EXPECT_FALSE(r.sweep.moving());
      EXPECT_FALSE(soon.sweep.moving());
      continue;
    }
    EXPECT_TRUE(r.sweep.angular_velocity.isApprox(Vec3(0.0, 0.0, 0.5), 1e-12));
    EXPECT_TRUE(r.sweep.velocity.isApprox(moved / 0.025, 1e-9)) << r.sweep.velocity.transpose();
    EXPECT_TRUE(soon.sweep.angular_velocity.isApprox(Vec3(0.0, 0.0, 0.5), 1e-12));
    EXPECT_TRUE(soon.sweep.velocity.isZero()) << soon.sweep.velocity.transpose();
  }
}

TEST_F(PipelineInRoom, ARejectedScanWithAPriorIsDeadReckoned) {
  config.nearest_neighbour.index = IndexKind::Exact;
  config.icp.max_error_after = 0.0;  // every match fails the error check
  SlamPipeline slam(config, start);
  slam.add_imu(level_imu(0.0));
  slam.add_imu(level_imu(0.1));
  ASSERT_TRUE(slam.process_scan(room.scan_at(pose_at(start, 0.0), 0.0)).accepted());
  const ScanReport r = slam.process_scan(room.scan_at(pose_at(start + Vec3(0.2, 0, 0), 0.1), 0.1),
                                         {Vec3(0.2, 0, 0), std::nullopt});
  EXPECT_EQ(r.outcome, ScanOutcome::ErrorTooLarge);
  EXPECT_TRUE(r.dead_reckoned);
  EXPECT_TRUE(r.pose.position.isApprox(start + Vec3(0.2, 0, 0)));
  EXPECT_TRUE(slam.pose().position.isApprox(start + Vec3(0.2, 0, 0)));
}

// Beyond the seed (icp.prior_gate): the prior, sure to 1 cm, says the vehicle moved 0.2 m; the
// scan says it stayed. Six sigmas and more apart: the match is rejected, counted, and the pose is
// the prior's. Without the check the match is taken; so it is before the match noise has settled
// (the gate measures in its scales).
// A planar scanner has no floor beams: its z is not the scan's to measure, and a room that fixes
// both horizontal directions leaves nothing degenerate (the tracking state stays `tracking`).
TEST_F(PipelineInRoom, APlanarScannersHeightIsNotCalledDegenerate) {
  config.nearest_neighbour.index = IndexKind::Exact;
  config.degeneracy.threshold = 0.05;
  ASSERT_TRUE(config.icp.split_axes);
  SlamPipeline slam(config, start);
  const double t = hover_to_settle(slam, 3);
  slam.add_imu(level_imu(t));
  const ScanReport r = slam.process_scan(room.scan_at(pose_at(start, t), t),
                                         {Vec3::Zero(), 1e-4 * Eigen::Matrix3d::Identity()});
  ASSERT_EQ(r.outcome, ScanOutcome::Accepted);
  EXPECT_EQ(r.seen.degenerate, 0);
  EXPECT_EQ(r.seen.observed(2, 2), 0.0) << "nor is it measured";
}

// With floor beams (the first 30 turned into a fan about straight down, as a mirror deflects
// them), the floor's level taken over the first second measures the height afterwards
// (floor.level_gate), and the height's variance is the fused one, under the floor's own; a floor
// that is not the level's (the vehicle over a 0.5 m platform, beyond the pairing distance, where
// the match cannot follow it as a drop of the vehicle) measures nothing.
TEST_F(PipelineInRoom, TheFloorsLevelMeasuresTheHeightWhereThatFloorIsSeen) {
  auto geometry = std::make_shared<ScanGeometry>(*room.geometry);
  for (std::size_t i = 0; i < 30; ++i) {
    const double across = (double(i) - 14.5) / 14.5 * 10.0 * M_PI / 180.0;
    geometry->directions[i] = Vec3(0.0, std::sin(across), -std::cos(across));
  }
  room.geometry = geometry;
  config.nearest_neighbour.index = IndexKind::Exact;
  config.degeneracy.threshold = 0.05;  // gives the match its covariance
  config.floor.level_gate = 0.1;
  config.floor.flatness = 0.01;
  SlamPipeline slam(config, start);
  double t = 0.0;
  const auto hover = [&](double until) {
    ScanReport last;
    for (; t < until; t += 0.025) {
      slam.add_imu(level_imu(t));
      last = slam.process_scan(room.scan_at(pose_at(start, t), t),
                               {Vec3::Zero(), 1e-4 * Eigen::Matrix3d::Identity()});
    }
    return last;
  };
  EXPECT_FALSE(hover(0.9).height_from_floor) << "the level is still being taken";
  const ScanReport measured = hover(1.5);
  ASSERT_TRUE(measured.accepted());
  EXPECT_TRUE(measured.height_from_floor);
  EXPECT_NEAR(measured.pose.position.z(), start.z(), 1e-3);
  EXPECT_GT(measured.covariance(2, 2), 0.0);
  EXPECT_LE(measured.covariance(2, 2), 0.01 * 0.01 + 1e-9) << "no surer than the floor's flatness";
  EXPECT_EQ(measured.map_covariance(2, 2), 0.0) << "absolute: no map under it";

  room.lo.z() = 0.5;  // a platform under the whole scan
  slam.add_imu(level_imu(t));
  const ScanReport platform = slam.process_scan(room.scan_at(pose_at(start, t), t),
                                                {Vec3::Zero(), 1e-4 * Eigen::Matrix3d::Identity()});
  EXPECT_FALSE(platform.height_from_floor);
}

TEST_F(PipelineInRoom, AMatchThatDisagreesWithThePriorIsRejected) {
  config.nearest_neighbour.index = IndexKind::Exact;
  config.degeneracy.threshold = 0.05;  // gives the match its covariance
  const auto disagreeing_scan = [&](double gate, int settle_scans) {
    config.icp.prior_gate = gate;
    SlamPipeline slam(config, start);
    const double t = hover_to_settle(slam, settle_scans);
    slam.add_imu(level_imu(t));
    const MotionPrediction prior{Vec3(0.2, 0, 0), 1e-4 * Eigen::Matrix3d::Identity()};
    ScanReport r = slam.process_scan(room.scan_at(pose_at(start, t), t), prior);
    EXPECT_EQ(slam.outcome_counts()[std::size_t(ScanOutcome::DisagreesWithPrior)],
              r.outcome == ScanOutcome::DisagreesWithPrior ? 1u : 0u);
    return r;
  };

  const ScanReport gated = disagreeing_scan(5.0, 120);
  EXPECT_EQ(gated.outcome, ScanOutcome::DisagreesWithPrior);
  EXPECT_GT(gated.prior_distance, 5.0);
  EXPECT_TRUE(gated.dead_reckoned);
  EXPECT_TRUE(gated.pose.position.isApprox(start + Vec3(0.2, 0, 0)));

  const ScanReport taken = disagreeing_scan(0.0, 120);
  ASSERT_EQ(taken.outcome, ScanOutcome::Accepted);
  EXPECT_GT(taken.prior_distance, 5.0) << "measured, though not checked";
  EXPECT_LT((taken.pose.position - start).head<2>().norm(), 0.01);

  const ScanReport unsettled = disagreeing_scan(5.0, 10);
  EXPECT_EQ(unsettled.outcome, ScanOutcome::Accepted);
  EXPECT_GT(unsettled.prior_distance, 5.0);

  // A prior that agrees (1 cm off, sure to 1 cm) passes the same check.
  config.icp.prior_gate = 5.0;
  SlamPipeline slam(config, start);
  const double t = hover_to_settle(slam);
  slam.add_imu(level_imu(t));
  const ScanReport agreed =
      slam.process_scan(room.scan_at(pose_at(start + Vec3(0.01, 0, 0), t), t),
                        {Vec3(0.02, 0, 0), 1e-4 * Eigen::Matrix3d::Identity()});
  EXPECT_EQ(agreed.outcome, ScanOutcome::Accepted);
  EXPECT_LT(agreed.prior_distance, 5.0);
}

// The prior jumps 0.2 m once (a knock, a glitch) while the vehicle hovers, and is right again
// after. The gate turns the matches away, each agreeing with the last; without a way out
// (prior_gate_overrule 0) the pose keeps the 0.2 m for good; with it, the fourth such match is
// taken and the pose is back.
TEST_F(PipelineInRoom, ARunOfMatchesThatAgreeWithEachOtherOverrulesAPriorThatJumped) {
  config.nearest_neighbour.index = IndexKind::Exact;
  config.degeneracy.threshold = 0.05;
  config.icp.prior_gate = 5.0;
  const auto hover = [&](int overrule) {
    config.icp.prior_gate_overrule = overrule;
    SlamPipeline slam(config, start);
    const double t0 = hover_to_settle(slam);
    std::vector<ScanReport> reports;
    for (int k = 0; k <= 8; ++k) {  // at 40 Hz, within recovery.gap of the last pose
      const double t = t0 + 0.025 * k;
      slam.add_imu(level_imu(t));
      const MotionPrediction prior{k == 1 ? Vec3(0.2, 0, 0) : Vec3::Zero(),
                                   1e-4 * Eigen::Matrix3d::Identity()};
      reports.push_back(slam.process_scan(room.scan_at(pose_at(start, t), t), prior));
    }
    return reports;
  };

  const std::vector<ScanReport> locked = hover(0);
  for (int k = 1; k <= 8; ++k) EXPECT_EQ(locked[k].outcome, ScanOutcome::DisagreesWithPrior) << k;
  EXPECT_NEAR((locked.back().pose.position - start).x(), 0.2, 1e-9);

  const std::vector<ScanReport> freed = hover(3);
  for (int k = 1; k <= 3; ++k) EXPECT_EQ(freed[k].outcome, ScanOutcome::DisagreesWithPrior) << k;
  EXPECT_EQ(freed[4].outcome, ScanOutcome::Accepted);
  EXPECT_TRUE(freed[4].prior_overruled);
  EXPECT_FALSE(freed[5].prior_overruled);
  for (int k = 4; k <= 8; ++k) {
    EXPECT_TRUE(freed[k].accepted()) << k;
    EXPECT_LT((freed[k].pose.position - start).head<2>().norm(), 0.01) << k;
  }
}

// Beyond the seed: after 2 s without scans (a link outage) the vehicle is 2.4 m on, beyond the
// seed's 1 m correction limit from the last position. With the recovery the ICP searches a grid
// of starts around it and finds the vehicle; without it (recovery.gap 0, the seed) it cannot.
TEST_F(PipelineInRoom, AfterAGapInTheScansTheMatcherFindsTheVehicleAgain) {
  config.nearest_neighbour.index = IndexKind::Exact;
  const auto truth_at = [&](double t) -> Vec3 { return start + Vec3(0.8 * t, 0.2 * t, 0.0); };
  const auto fly = [&](SlamPipeline& slam) {
    for (int k = 0; k <= 40; ++k) {  // 1 s of scans, then nothing until t = 3 s
      const double t = k / 40.0;
      slam.add_imu(level_imu(t));
      EXPECT_TRUE(slam.process_scan(room.scan_at(pose_at(truth_at(t), t), t)).accepted()) << k;
    }
    slam.add_imu(level_imu(3.0));
    return slam.process_scan(room.scan_at(pose_at(truth_at(3.0), 3.0), 3.0));
  };

  SlamPipeline recovering(config, start);
  const ScanReport found = fly(recovering);
  EXPECT_TRUE(found.relocalised);
  ASSERT_TRUE(found.accepted()) << to_string(found.outcome);
  EXPECT_LT((found.pose.position - truth_at(3.0)).head<2>().norm(), 0.05);

  config.recovery.gap = 0.0;
  SlamPipeline seed(config, start);
  const ScanReport lost = fly(seed);
  EXPECT_FALSE(lost.relocalised);
  EXPECT_FALSE(lost.accepted() && (lost.pose.position - truth_at(3.0)).head<2>().norm() < 0.5)
      << "the seed's single start cannot reach the vehicle 2.4 m away";
}

// The search grid: the start itself first, then outwards, all within the radius.
TEST(Relocalisation, TheStartsCoverTheDiscNearestFirst) {
  const Vec3 centre(1.0, 2.0, 1.5);
  const std::vector<Vec3> starts = search_starts(centre, 1.0, 0.5);
  ASSERT_FALSE(starts.empty());
  EXPECT_TRUE(starts.front().isApprox(centre));
  EXPECT_EQ(starts.size(), 13u);  // (0,0), 4 at 0.5, 4 at 0.71, 4 at 1.0
  double previous = 0.0;
  for (const Vec3& s : starts) {
    const double d = (s - centre).norm();
    EXPECT_LE(d, 1.0 + 1e-9);
    EXPECT_GE(d, previous - 1e-12);
    EXPECT_EQ(s.z(), centre.z());
    previous = d;
  }
  SlamConfig::Recovery recovery;
  EXPECT_DOUBLE_EQ(search_radius(recovery, 0.5), 1.0);   // 2 m/s x 0.5 s
  EXPECT_DOUBLE_EQ(search_radius(recovery, 10.0), 3.0);  // capped
}

}  // namespace
}  // namespace uavslam
