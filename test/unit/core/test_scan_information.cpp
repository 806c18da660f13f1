#include <cmath>

#include <gtest/gtest.h>

#include "core/extensions/ScanInformation.hpp"

namespace uavslam {
namespace {

constexpr double kThreshold = 0.05;
constexpr double kMinSigma = 0.01;

// Pairs on a wall through `from` along `direction`, seen from the origin, each with the wall's
// normal and a residual of 1 cm along it.
void add_wall(Correspondences& pairs, const Vec3& from, const Vec3& direction, double length) {
  const Vec3 normal(-direction.y(), direction.x(), 0.0);
  for (double s = 0.0; s <= length; s += 0.1) {
    const Vec3 m = from + s * direction;
    pairs.scan.push_back(m);
    pairs.map.push_back(m - 0.01 * normal);
    pairs.weights.emplace_back(1.0, 1.0, 0.0);
    pairs.scan_normals.push_back(normal);
  }
}

// An 8 x 6 m room's four walls about the origin.
void add_room(Correspondences& pairs) {
  add_wall(pairs, Vec3(-4, -3, 0), Vec3::UnitX(), 8.0);
  add_wall(pairs, Vec3(-4, 3, 0), Vec3::UnitX(), 8.0);
  add_wall(pairs, Vec3(-4, -3, 0), Vec3::UnitY(), 6.0);
  add_wall(pairs, Vec3(4, -3, 0), Vec3::UnitY(), 6.0);
}

void add_floor(Correspondences& pairs, int count) {
  for (int i = 0; i < count; ++i) {
    pairs.scan.emplace_back(0.1 * i, 0.0, -1.5);
    pairs.map.emplace_back(0.1 * i, 0.0, -1.5);
    pairs.weights.emplace_back(0.0, 0.0, 1.0);
    pairs.scan_normals.push_back(Vec3::Zero());
  }
}

Observability seen(const Correspondences& pairs, bool with_yaw, bool measures_height = false) {
  return observability(scan_information(pairs, Vec3::Zero(), with_yaw, kMinSigma), kThreshold,
                       measures_height);
}

TEST(ScanInformation, ACorridorLeavesItsAxisFree) {
  Correspondences pairs;
  add_wall(pairs, Vec3(-5, -1, 0), Vec3::UnitX(), 10.0);
  add_wall(pairs, Vec3(-5, 1, 0), Vec3::UnitX(), 10.0);
  for (bool with_yaw : {false, true}) {
    const Observability o = seen(pairs, with_yaw);
    EXPECT_EQ(o.degenerate, 1) << "with_yaw " << with_yaw;
    EXPECT_NEAR(std::abs(o.weakest.x()), 1.0, 1e-9);
    EXPECT_LT(o.weakest_fraction, 1e-9);
    // The axis keeps the prediction; across it the scan is kept.
    EXPECT_NEAR(o.observed(0, 0), 0.0, 1e-9);
    EXPECT_NEAR(o.observed(1, 1), 1.0, 1e-9);
    EXPECT_EQ(o.covariance(0, 0), 0.0);
    EXPECT_GT(o.covariance(1, 1), 0.0);
  }
}

TEST(ScanInformation, ASingleWallLeavesItsLengthFree) {
  Correspondences pairs;
  add_wall(pairs, Vec3(-3, 2, 0), Vec3(1, 1, 0).normalized(), 4.0);
  const Observability o = seen(pairs, false);
  EXPECT_EQ(o.degenerate, 1);
  EXPECT_NEAR(std::abs(o.weakest.dot(Vec3(1, 1, 0).normalized())), 1.0, 1e-9);
}

TEST(ScanInformation, ACornerFixesBothDirections) {
  Correspondences pairs;
  add_wall(pairs, Vec3(-4, 3, 0), Vec3::UnitX(), 8.0);
  add_wall(pairs, Vec3(3, -4, 0), Vec3::UnitY(), 3.0);
  const Observability o = seen(pairs, true);
  EXPECT_EQ(o.degenerate, 0);
  EXPECT_GT(o.weakest_fraction, kThreshold);
  const Eigen::Matrix2d horizontal = o.observed.topLeftCorner<2, 2>();
  EXPECT_TRUE(horizontal.isApprox(Eigen::Matrix2d::Identity()));
}

TEST(ScanInformation, AnOpenRoomFixesEverythingAndItsCovarianceIsSigmaSquaredOverTheInformation) {
  Correspondences pairs;
  add_room(pairs);
  add_floor(pairs, 20);
  const ScanInformation info = scan_information(pairs, Vec3::Zero(), false, kMinSigma);
  EXPECT_NEAR(info.sigma, 0.01, 1e-9);  // every pair 1 cm off along its normal
  const Observability o = observability(info, kThreshold, true);
  EXPECT_EQ(o.degenerate, 0);
  // The pairs on the two walls along y (61 each) fix x: sigma^2 / 122.
  const double walls_along_y = double(2 * 61);
  EXPECT_NEAR(o.covariance(0, 0), 1e-4 / walls_along_y, 1e-9);
  EXPECT_NEAR(o.covariance(2, 2), 1e-4 / 20.0, 1e-12);  // the floor's 20 pairs
}

// The yaw's variance, when the yaw is estimated beside the translation: sigma^2 over the yaw's
// information, in a room symmetric about the body the lever arms' sum of squares (nothing couples
// it to the translation there). Without the yaw estimated, none.
TEST(ScanInformation, TheYawsVarianceIsSigmaSquaredOverItsInformation) {
  Correspondences pairs;
  add_room(pairs);
  double lever_arms = 0.0;
  for (std::size_t i = 0; i < pairs.scan.size(); ++i) {
    const Vec3& n = pairs.scan_normals[i];
    const Vec3& q = pairs.scan[i];
    lever_arms += std::pow(-n.x() * q.y() + n.y() * q.x(), 2);
  }
  const ScanInformation info = scan_information(pairs, Vec3::Zero(), true, kMinSigma);
  EXPECT_NEAR(info.yaw_variance, 1e-4 / lever_arms, 1e-12);
  EXPECT_EQ(observability(info, kThreshold, false).yaw_variance, info.yaw_variance);
  EXPECT_EQ(scan_information(pairs, Vec3::Zero(), false, kMinSigma).yaw_variance, 0.0);
}

TEST(ScanInformation, HeightIsDegenerateOnlyForAScannerThatMeasuresIt) {
  Correspondences pairs;
  add_wall(pairs, Vec3(-4, 3, 0), Vec3::UnitX(), 8.0);
  add_wall(pairs, Vec3(3, -4, 0), Vec3::UnitY(), 3.0);
  EXPECT_EQ(seen(pairs, false, false).degenerate, 0) << "a planar scanner never measures z";
  EXPECT_EQ(seen(pairs, false, true).degenerate, 1) << "a floor mirror that saw no floor";
  EXPECT_EQ(seen(pairs, false, true).observed(2, 2), 0.0);
}

TEST(ScanInformation, NoScanNormalsGiveNoInformation) {
  Correspondences pairs;
  add_wall(pairs, Vec3(-4, 3, 0), Vec3::UnitX(), 8.0);
  pairs.scan_normals.clear();
  const ScanInformation info = scan_information(pairs, Vec3::Zero(), false, kMinSigma);
  EXPECT_TRUE(info.translation.isZero());
  EXPECT_EQ(observability(info, kThreshold, false).degenerate, 2);
}

}  // namespace
}  // namespace uavslam
