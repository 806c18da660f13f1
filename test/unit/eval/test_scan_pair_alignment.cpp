// The scans' own alignment of a relation (eval/ScanPairAlignment) in a synthetic room: it finds
// the motion the scans show from a start near it, so a relation that is off is shown to be off.
#include <cmath>

#include <gtest/gtest.h>

#include "core/Heading.hpp"
#include "eval/ScanPairAlignment.hpp"
#include "io/SlamConfigFile.hpp"
#include "unit/core/SyntheticRoom.hpp"

namespace {

using uavslam::Pose;
using uavslam::ScanOutcome;
using uavslam::SlamConfig;
using uavslam::Vec3;
using uavslam::yaw_rotation;
using uavslam::eval::align_scan_pair;
using uavslam::eval::Relation;
using uavslam::eval::ScanPairAlignment;

Pose planar_pose(double x, double y, double yaw) {
  return {0.0, Vec3(x, y, 1.0), yaw_rotation(yaw)};
}

// The motion from a to b in a's frame.
Relation relation_between(const Pose& a, const Pose& b, double yaw_a, double yaw_b) {
  const Vec3 d = a.orientation.inverse() * (b.position - a.position);
  return {1.0, 2.0, d.x(), d.y(), std::remainder(yaw_b - yaw_a, 2.0 * M_PI)};
}

SlamConfig shipped_2d_config() {
  return uavslam::io::load_slam_config(std::string(UAVSLAM_SOURCE_DIR) +
                                       "/config/slam_2d_logs.yaml");
}

class ScanPairAlignmentTest : public ::testing::Test {
 protected:
  uavslam::test::SyntheticRoom room;
  const Pose a = planar_pose(3.0, 3.0, 0.1);
  const Pose b = planar_pose(3.3, 3.1, 0.25);
  const Relation truth = relation_between(a, b, 0.1, 0.25);
};

TEST_F(ScanPairAlignmentTest, FindsTheMotionTheScansShowFromAStartNearIt) {
  Relation off = truth;
  off.x += 0.05;
  off.y -= 0.03;
  off.yaw += 0.02;
  const ScanPairAlignment found =
      align_scan_pair(room.scan_at(a, 1.0), room.scan_at(b, 2.0), off, shipped_2d_config());
  ASSERT_EQ(found.outcome, ScanOutcome::Accepted);
  EXPECT_NEAR(found.motion.x, truth.x, 2e-3);
  EXPECT_NEAR(found.motion.y, truth.y, 2e-3);
  EXPECT_NEAR(found.motion.yaw, truth.yaw, 2e-3);
  EXPECT_EQ(found.motion.t1, truth.t1);
  EXPECT_EQ(found.motion.t2, truth.t2);
}

TEST_F(ScanPairAlignmentTest, AnExactRelationIsLeftWhereItIs) {
  const ScanPairAlignment found =
      align_scan_pair(room.scan_at(a, 1.0), room.scan_at(b, 2.0), truth, shipped_2d_config());
  ASSERT_EQ(found.outcome, ScanOutcome::Accepted);
  EXPECT_NEAR(found.motion.x, truth.x, 1e-3);
  EXPECT_NEAR(found.motion.y, truth.y, 1e-3);
  EXPECT_NEAR(found.motion.yaw, truth.yaw, 1e-3);
}

// The seed's mode keeps the relation's yaw and finds only the translation.
TEST_F(ScanPairAlignmentTest, TheSeedsTranslationOnlyModeKeepsTheRelationsYaw) {
  SlamConfig seed = shipped_2d_config();
  seed.icp.heading = uavslam::HeadingMode::Source;
  Relation off = truth;
  off.x -= 0.04;
  const ScanPairAlignment found =
      align_scan_pair(room.scan_at(a, 1.0), room.scan_at(b, 2.0), off, seed);
  ASSERT_EQ(found.outcome, ScanOutcome::Accepted);
  EXPECT_EQ(found.motion.yaw, truth.yaw);
  EXPECT_NEAR(found.motion.x, truth.x, 2e-3);
  EXPECT_NEAR(found.motion.y, truth.y, 2e-3);
}

// Scans of two different places share nothing within the pairing gate: no alignment.
TEST_F(ScanPairAlignmentTest, ScansThatDoNotOverlapAreNotAligned) {
  uavslam::test::SyntheticRoom other;
  other.lo = Vec3(-20, -20, 0);
  other.hi = Vec3(20, 20, 3);
  other.pillar_lo = Vec3(-19, -19, 0);
  other.pillar_hi = Vec3(-18, -18, 3);
  const ScanPairAlignment found =
      align_scan_pair(room.scan_at(a, 1.0), other.scan_at(b, 2.0), truth, shipped_2d_config());
  EXPECT_NE(found.outcome, ScanOutcome::Accepted);
  EXPECT_EQ(found.motion.x, truth.x);
}

}  // namespace
