// The offline variant's dense cloud: every valid return placed by the scan's pose, one centroid
// per voxel.
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include <gtest/gtest.h>

#include "maps/DenseCloud.hpp"

namespace uavslam {
namespace {

Scan four_beam_scan(double stamp) {
  auto geometry = std::make_shared<ScanGeometry>(ScanGeometry::planar(0.0, M_PI / 2, 4));
  geometry->mount = Eigen::Translation3d(0.1, 0.0, 0.2) * Eigen::Isometry3d::Identity();
  Scan scan;
  scan.stamp = stamp;
  scan.geometry = geometry;
  // beam 2 has no return, beam 3 is below the minimum range
  scan.ranges = {1.0f, 2.0f, std::numeric_limits<float>::quiet_NaN(), 0.01f};
  scan.intensities = {10.0f, 20.0f, 30.0f, 40.0f};
  return scan;
}

TEST(DenseCloud, PlacesEveryValidReturnByThePoseAndTheMount) {
  DenseCloud cloud(0.0);
  Pose pose;
  pose.position = Vec3(5.0, 0.0, 1.0);
  pose.orientation = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ());
  cloud.add_scan(four_beam_scan(3.0), pose);
  const std::vector<DensePoint> points = cloud.points();
  ASSERT_EQ(points.size(), 2u);
  // beam 0 (sensor +x, 1 m) -> body (1.1, 0, 0.2) -> world: yaw 90 deg, then + (5, 0, 1)
  EXPECT_TRUE(points[0].position.isApprox(Vec3(5.0, 1.1, 1.2), 1e-9)) << points[0].position;
  EXPECT_FLOAT_EQ(points[0].intensity, 10.0f);
  EXPECT_DOUBLE_EQ(points[0].time, 3.0);
  // beam 1 (sensor +y, 2 m) -> body (0.1, 2, 0.2) -> world (5 - 2, 0.1, 1.2)
  EXPECT_TRUE(points[1].position.isApprox(Vec3(3.0, 0.1, 1.2), 1e-9)) << points[1].position;
  EXPECT_EQ(cloud.points_added(), 2u);
}

TEST(DenseCloud, KeepsTheCentroidOfEachVoxel) {
  DenseCloud cloud(0.1);
  cloud.add_point(Vec3(0.01, 0.01, 0.01), 1.0f, 2.0);
  cloud.add_point(Vec3(0.03, 0.05, 0.09), 3.0f, 1.0);
  cloud.add_point(Vec3(0.15, 0.0, 0.0), 5.0f, 0.5);   // the next voxel along x
  cloud.add_point(Vec3(-0.01, 0.0, 0.0), 7.0f, 4.0);  // below zero: its own voxel
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.points_added(), 4u);
  const std::vector<DensePoint> points = cloud.points();  // in the order first hit
  ASSERT_EQ(points.size(), 3u);
  EXPECT_TRUE(points[0].position.isApprox(Vec3(0.02, 0.03, 0.05), 1e-6)) << points[0].position;
  EXPECT_FLOAT_EQ(points[0].intensity, 2.0f);
  EXPECT_DOUBLE_EQ(points[0].time, 2.0) << "the time of the voxel's first point";
  EXPECT_TRUE(points[1].position.isApprox(Vec3(0.15, 0.0, 0.0), 1e-6));
  EXPECT_TRUE(points[2].position.isApprox(Vec3(-0.01, 0.0, 0.0), 1e-6));
}

TEST(DenseCloud, ManyVoxelsSurviveTheTableGrowing) {
  DenseCloud cloud(0.01);
  for (int i = 0; i < 5000; ++i) {
    for (int copy = 0; copy < 3; ++copy)
      cloud.add_point(Vec3(0.01 * i + 0.005, -3.0, 2.0), 1.0f, i);
  }
  ASSERT_EQ(cloud.size(), 5000u);
  const std::vector<DensePoint> points = cloud.points();
  for (int i = 0; i < 5000; ++i) {
    ASSERT_NEAR(points[i].position.x(), 0.01 * i + 0.005, 1e-7) << i;
    ASSERT_EQ(points[i].time, double(i));
  }
}

TEST(DenseCloud, DropsPointsItCannotPlace) {
  DenseCloud cloud(0.01);
  cloud.add_point(Vec3(std::nan(""), 0.0, 0.0), 0.0f, 0.0);
  cloud.add_point(Vec3(1e12, 0.0, 0.0), 0.0f, 0.0);  // beyond an int voxel key
  cloud.add_point(Vec3(1.0, 2.0, 3.0), 0.0f, 0.0);
  EXPECT_EQ(cloud.size(), 1u);
}

TEST(DenseCloud, RefusesANonFiniteVoxel) {
  EXPECT_THROW(DenseCloud(std::numeric_limits<double>::infinity()), std::invalid_argument);
}

}  // namespace
}  // namespace uavslam
