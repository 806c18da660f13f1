#include <limits>

#include <gtest/gtest.h>

#include "core/SlamConfig.hpp"
#include "slam/OdometryPrior.hpp"

namespace uavslam {
namespace {

OdometrySample at(double stamp, double x, double y) {
  return {stamp, Vec3(x, y, 0.0)};
}

TEST(OdometryPrior, IsTheOdometryMotionSinceTheLastPosedScan) {
  OdometryPrior prior(0.1, SlamConfig::Motion{});
  prior.add(at(1.0, 1.0, 1.0));
  prior.add(at(1.2, 1.5, 1.0));
  prior.add(at(1.4, 2.0, 1.5));
  EXPECT_EQ(prior.motion_to(1.0).motion, Vec3::Zero()) << "no scan got a pose yet";
  prior.scan_posed(1.0, Eigen::Matrix3d::Zero());
  EXPECT_EQ(prior.motion_to(1.2).motion, Vec3(0.5, 0.0, 0.0));
  // The scan at 1.2 got no pose (rejected): the next motion still starts at 1.0.
  EXPECT_EQ(prior.motion_to(1.4).motion, Vec3(1.0, 0.5, 0.0));
  prior.scan_posed(1.4, Eigen::Matrix3d::Zero());
  prior.add(at(1.6, 2.0, 2.5));
  EXPECT_EQ(prior.motion_to(1.6).motion, Vec3(0.0, 1.0, 0.0));
  EXPECT_EQ(prior.scans_with_prior(), 3u);
  EXPECT_EQ(prior.scans_without_prior(), 1u);
}

// Sigma = Sigma_posed + (floor + per_metre |motion|)^2 I: the pose's own uncertainty, grown with
// the distance the wheels rolled.
TEST(OdometryPrior, ItsCovarianceGrowsWithTheDistanceFromThePosedScansOwn) {
  SlamConfig::Motion noise;
  noise.odometry_noise_per_metre = 0.1;
  noise.odometry_noise_floor = 0.01;
  OdometryPrior prior(0.1, noise);
  prior.add(at(1.0, 0.0, 0.0));
  prior.add(at(1.1, 2.0, 0.0));
  EXPECT_FALSE(prior.motion_to(1.0).covariance) << "unknown: no covariance either";
  prior.scan_posed(1.0, 0.0004 * Eigen::Matrix3d::Identity());
  const MotionPrediction p = prior.motion_to(1.1);
  ASSERT_TRUE(p.covariance);
  const double sigma = 0.01 + 0.1 * 2.0;
  EXPECT_NEAR((*p.covariance)(0, 0), 0.0004 + sigma * sigma, 1e-12);
  EXPECT_NEAR((*p.covariance)(0, 1), 0.0, 1e-12);
}

TEST(OdometryPrior, IsZeroAndCountedWhenTheOdometryIsUnknownAtEitherEnd) {
  OdometryPrior prior(0.1, SlamConfig::Motion{});
  prior.add(at(1.0, 0.0, 0.0));
  prior.scan_posed(1.0, Eigen::Matrix3d::Zero());
  EXPECT_EQ(prior.motion_to(2.0).motion, Vec3::Zero()) << "no sample near the scan";
  prior.scan_posed(2.0, Eigen::Matrix3d::Zero());
  prior.add(at(2.1, 1.0, 0.0));
  EXPECT_EQ(prior.motion_to(2.1).motion, Vec3::Zero()) << "no sample near the last posed scan";
  EXPECT_EQ(prior.scans_with_prior(), 0u);
  EXPECT_EQ(prior.scans_without_prior(), 2u);
}

TEST(OdometryPrior, CountsTheBadSamplesItDrops) {
  OdometryPrior prior(0.1, SlamConfig::Motion{});
  EXPECT_FALSE(prior.add(at(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0)));
  EXPECT_TRUE(prior.add(at(1.0, 0.0, 0.0)));
  EXPECT_FALSE(prior.add(at(1.1, std::numeric_limits<double>::infinity(), 0.0)));
  EXPECT_EQ(prior.rejected(), 2u);
}

}  // namespace
}  // namespace uavslam
