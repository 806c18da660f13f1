// The beam geometry of a LiDAR description: planar, mirrored, mounted, multi-ring.
#include <cmath>

#include <gtest/gtest.h>

#include "core/Angles.hpp"
#include "sensor/LidarGeometry.hpp"
#include "unit/sensor/ThreeBeamLidar.hpp"

namespace uavslam {
namespace {

using test::three_beam_lidar;

TEST(LidarGeometry, PlanarBeamsSpanTheFieldOfViewAroundX) {
  const LidarSpec spec;  // the Hokuyo defaults: 1080 beams over 270 degrees
  const auto geometry = make_scan_geometry(spec);
  ASSERT_EQ(geometry->directions.size(), 1080u);
  const double first = deg_to_rad(-135.0);
  EXPECT_LT((geometry->directions.front() - Vec3(std::cos(first), std::sin(first), 0.0)).norm(),
            1e-12);
  EXPECT_LT((geometry->directions.back() - Vec3(std::cos(-first), std::sin(-first), 0.0)).norm(),
            1e-12);
  EXPECT_DOUBLE_EQ(geometry->min_range, 0.1);
  EXPECT_DOUBLE_EQ(geometry->max_range, 30.0);
  EXPECT_LT((geometry->mount.translation() - Vec3(0.0, 0.0, 0.1)).norm(), 1e-15);
  EXPECT_TRUE(geometry->mount.linear().isIdentity(1e-15));
}

TEST(LidarGeometry, MountRotationIsRollPitchYaw) {
  LidarSpec spec = three_beam_lidar();
  spec.mount_rpy_deg = Vec3(0.0, 90.0, 0.0);  // pitched to look straight down
  const auto geometry = make_scan_geometry(spec);
  EXPECT_LT((geometry->mount.linear() * Vec3::UnitX() - (-Vec3::UnitZ())).norm(), 1e-12);
  spec.mount_rpy_deg = Vec3(10.0, 20.0, 30.0);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(deg_to_rad(30.0), Vec3::UnitZ()) *
                                    Eigen::AngleAxisd(deg_to_rad(20.0), Vec3::UnitY()) *
                                    Eigen::AngleAxisd(deg_to_rad(10.0), Vec3::UnitX()))
                                       .toRotationMatrix();
  EXPECT_TRUE(make_scan_geometry(spec)->mount.linear().isApprox(expected, 1e-12));
}

TEST(LidarGeometry, FloorMirrorBeamsFanDownwardInTheFirstBeamsPlane) {
  LidarSpec spec;
  spec.floor_mirror.beams = 30;
  spec.floor_mirror.spread_deg = 20.0;
  const auto geometry = make_scan_geometry(spec);
  const double azimuth = deg_to_rad(-135.0);
  const Vec3 plane_normal(-std::sin(azimuth), std::cos(azimuth), 0.0);
  for (int i = 0; i < 30; ++i) {
    const Vec3& d = geometry->directions[static_cast<std::size_t>(i)];
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);
    EXPECT_NEAR(d.dot(plane_normal), 0.0, 1e-12);            // in the vertical plane
    EXPECT_LE(std::acos(-d.z()), deg_to_rad(10.0) + 1e-12);  // within the fan
  }
  EXPECT_NEAR(std::acos(-geometry->directions[0].z()), deg_to_rad(10.0), 1e-12);
  EXPECT_NEAR(std::acos(-geometry->directions[29].z()), deg_to_rad(10.0), 1e-12);
  EXPECT_EQ(geometry->directions[30].z(), 0.0);  // the rest stay planar
}

// A real UTM-30LX's own layout (1081 steps of 0.25 deg from -135 deg) on the configured mount and
// mirror: the beams where the scans say, the mirror's fan in the plane of their first beam.
TEST(LidarGeometry, AScansOwnLayoutKeepsTheSensorsMountAndMirror) {
  LidarSpec spec;  // 1080 beams over 270 deg
  spec.mount_position = Vec3(0.05, 0.0, 0.1);
  spec.floor_mirror.beams = 30;
  spec.floor_mirror.spread_deg = 20.0;
  const double first = deg_to_rad(-135.0);
  const double step = deg_to_rad(0.25);
  const ScanGeometry geometry = planar_scan_geometry(spec, first, step, 1081);
  ASSERT_EQ(geometry.directions.size(), 1081u);
  EXPECT_NEAR(geometry.directions[540].x(), 1.0, 1e-12);  // the middle step looks ahead
  EXPECT_NEAR(std::atan2(geometry.directions[1080].y(), geometry.directions[1080].x()),
              deg_to_rad(135.0), 1e-12);
  const Vec3 plane_normal(-std::sin(first), std::cos(first), 0.0);
  EXPECT_NEAR(geometry.directions[0].dot(plane_normal), 0.0, 1e-12);
  EXPECT_LT(geometry.directions[29].z(), -0.9);  // mirrored
  EXPECT_EQ(geometry.directions[30].z(), 0.0);
  EXPECT_TRUE(geometry.mount.translation().isApprox(spec.mount_position));
  EXPECT_EQ(geometry.max_range, spec.max_range);

  // The configured layout is the same construction.
  const auto configured = make_scan_geometry(spec);
  const ScanGeometry same =
      planar_scan_geometry(spec, -deg_to_rad(135.0), deg_to_rad(270.0) / 1079, 1080);
  ASSERT_EQ(configured->directions.size(), same.directions.size());
  for (std::size_t i = 0; i < same.directions.size(); ++i) {
    EXPECT_TRUE(configured->directions[i].isApprox(same.directions[i], 1e-12)) << i;
  }
}

TEST(LidarGeometry, MultiRingHasBeamsTimesRingsDirections) {
  LidarSpec spec;
  spec.beams = 360;
  spec.rings = 16;
  spec.vertical_fov_deg = 30.0;
  spec.floor_mirror.beams = 30;  // ignored with rings
  const auto geometry = make_scan_geometry(spec);
  ASSERT_EQ(geometry->directions.size(), 360u * 16u);
  EXPECT_NEAR(std::asin(geometry->directions.front().z()), deg_to_rad(-15.0), 1e-12);
  EXPECT_NEAR(std::asin(geometry->directions.back().z()), deg_to_rad(15.0), 1e-12);
}

}  // namespace
}  // namespace uavslam
