#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/ScanProjection.hpp"

namespace uavslam {
namespace {

std::shared_ptr<ScanGeometry> three_beams() {
  auto g = std::make_shared<ScanGeometry>(ScanGeometry::planar(-M_PI / 2, M_PI / 2, 3));
  g->min_range = 0.1;
  g->max_range = 30.0;
  return g;
}

TEST(ScanProjection, InvalidRangesAreDroppedAndCounted) {
  const ScanGeometry g = *three_beams();
  EXPECT_TRUE(is_valid_range(1.0f, g));
  EXPECT_TRUE(is_valid_range(30.0f, g));
  EXPECT_FALSE(is_valid_range(0.05f, g));
  EXPECT_FALSE(is_valid_range(30.5f, g));
  EXPECT_FALSE(is_valid_range(std::numeric_limits<float>::quiet_NaN(), g));
  EXPECT_FALSE(is_valid_range(std::numeric_limits<float>::infinity(), g));

  Scan scan;
  scan.geometry = three_beams();
  scan.ranges = {1.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f};
  const ProjectedScan p = project_scan(scan, Eigen::Quaterniond::Identity());
  EXPECT_EQ(p.points.size(), 1u);
  EXPECT_EQ(p.invalid, 2u);
  EXPECT_NEAR(p.points[0].y(), -1.0, 1e-12);
}

TEST(ScanProjection, AppliesOrientationAndMount) {
  auto g = three_beams();
  g->mount.translation() = Vec3(0.0, 0.0, 0.1);
  Scan scan;
  scan.geometry = g;
  scan.ranges = {2.0f, 2.0f, 2.0f};
  // Yawed by 90 degrees: the forward beam (index 1, +x of the sensor) points along world +y.
  const Eigen::Quaterniond yaw90(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
  const ProjectedScan p = project_scan(scan, yaw90);
  ASSERT_EQ(p.points.size(), 3u);
  EXPECT_TRUE(p.points[1].isApprox(Vec3(0.0, 2.0, 0.1), 1e-9)) << p.points[1].transpose();
  // Pitched nose-down by 90 degrees the forward beam points at the floor, mount offset forward.
  const Eigen::Quaterniond pitch(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()));
  const ProjectedScan q = project_scan(scan, pitch);
  EXPECT_TRUE(q.points[1].isApprox(Vec3(0.1, 0.0, -2.0), 1e-9)) << q.points[1].transpose();
}

// A body turning and moving while its three beams fire 10 ms apart: each beam's point is where that
// beam hit from where the body was then, p_i = R Exp(omega t_i) (mount (r d_i)) + v t_i; without
// the sweep's motion every beam is placed from the stamp's pose.
TEST(ScanProjection, EachBeamIsPlacedFromWhereTheBodyWasWhenItFired) {
  auto g = three_beams();
  g->mount.translation() = Vec3(0.1, 0.0, 0.05);
  g->sweep_beams_in_order(0.01);
  ASSERT_EQ(g->fire_times, (std::vector<double>{0.0, 0.01, 0.02}));
  Scan scan;
  scan.geometry = g;
  scan.ranges = {2.0f, 3.0f, 4.0f};
  const Eigen::Quaterniond orientation(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
  SweepMotion sweep;
  sweep.angular_velocity = Vec3(0.0, 0.0, 2.0);  // rad/s, body frame
  sweep.velocity = Vec3(1.5, -0.5, 0.0);         // m/s, world frame
  const ProjectedScan p = project_scan(scan, orientation, sweep);
  const ProjectedScan still = project_scan(scan, orientation);
  ASSERT_EQ(p.points.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const double t = 0.01 * double(i);
    Eigen::Isometry3d body = Eigen::Isometry3d::Identity();
    body.linear() = Eigen::AngleAxisd(0.3 + 2.0 * t, Vec3::UnitZ()).toRotationMatrix();
    body.translation() = sweep.velocity * t;
    const Vec3 hit = body * g->mount * (double(scan.ranges[i]) * g->directions[i]);
    EXPECT_TRUE(p.points[i].isApprox(hit, 1e-12))
        << "beam " << i << ": " << p.points[i].transpose();
  }
  EXPECT_TRUE(p.points[0].isApprox(still.points[0], 1e-12));
  EXPECT_GT((p.points[2] - still.points[2]).norm(), 0.05);  // 0.04 rad at 4 m and 3 cm moved
}

TEST(ScanProjection, KeepsEveryKthPointAsTheSeed) {
  Points points(1080, Vec3::Zero());
  for (std::size_t i = 0; i < points.size(); ++i) points[i].x() = double(i);
  const Points kept = keep_every_kth(points, 5);
  ASSERT_EQ(kept.size(), 216u);
  EXPECT_EQ(kept[0].x(), 0.0);
  EXPECT_EQ(kept[1].x(), 5.0);
  EXPECT_EQ(keep_every_kth(points, 1).size(), 1080u);
  EXPECT_EQ(keep_every_kth(Points{}, 5).size(), 0u);
}

// Whether a sensor can measure height: a planar scanner cannot; a floor mirror's beams, or the
// same planar scanner mounted on its side, can.
TEST(ScanGeometry, HasVerticalBeamsWhenSomePointUpOrDownOnTheBody) {
  ScanGeometry planar = ScanGeometry::planar(-M_PI / 2, M_PI / 180, 181);
  EXPECT_FALSE(planar.has_vertical_beams());
  ScanGeometry mirrored = planar;
  mirrored.directions.front() = Vec3(std::cos(1.3), 0.0, -std::sin(1.3));  // 74 deg down
  EXPECT_TRUE(mirrored.has_vertical_beams());
  ScanGeometry on_its_side = planar;
  on_its_side.mount.linear() = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix();
  EXPECT_TRUE(on_its_side.has_vertical_beams());
}

}  // namespace
}  // namespace uavslam
