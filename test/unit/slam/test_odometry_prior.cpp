#include <limits>

#include <gtest/gtest.h>

#include "slam/OdometryPrior.hpp"

namespace uavslam {
namespace {

OdometrySample at(double stamp, double x, double y) {
  return {stamp, Vec3(x, y, 0.0)};
}

TEST(OdometryPrior, IsTheOdometryMotionSinceTheLastPosedScan) {
  OdometryPrior prior(0.1);
  prior.add(at(1.0, 1.0, 1.0));
  prior.add(at(1.2, 1.5, 1.0));
  prior.add(at(1.4, 2.0, 1.5));
  EXPECT_EQ(prior.motion_to(1.0), Vec3::Zero()) << "no scan got a pose yet";
  prior.scan_posed(1.0);
  EXPECT_EQ(prior.motion_to(1.2), Vec3(0.5, 0.0, 0.0));
  // The scan at 1.2 got no pose (rejected): the next motion still starts at 1.0.
  EXPECT_EQ(prior.motion_to(1.4), Vec3(1.0, 0.5, 0.0));
  prior.scan_posed(1.4);
  prior.add(at(1.6, 2.0, 2.5));
  EXPECT_EQ(prior.motion_to(1.6), Vec3(0.0, 1.0, 0.0));
  EXPECT_EQ(prior.scans_with_prior(), 3u);
  EXPECT_EQ(prior.scans_without_prior(), 1u);
}

TEST(OdometryPrior, IsZeroAndCountedWhenTheOdometryIsUnknownAtEitherEnd) {
  OdometryPrior prior(0.1);
  prior.add(at(1.0, 0.0, 0.0));
  prior.scan_posed(1.0);
  EXPECT_EQ(prior.motion_to(2.0), Vec3::Zero()) << "no sample near the scan";
  prior.scan_posed(2.0);
  prior.add(at(2.1, 1.0, 0.0));
  EXPECT_EQ(prior.motion_to(2.1), Vec3::Zero()) << "no sample near the last posed scan";
  EXPECT_EQ(prior.scans_with_prior(), 0u);
  EXPECT_EQ(prior.scans_without_prior(), 2u);
}

TEST(OdometryPrior, CountsTheBadSamplesItDrops) {
  OdometryPrior prior(0.1);
  EXPECT_FALSE(prior.add(at(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0)));
  EXPECT_TRUE(prior.add(at(1.0, 0.0, 0.0)));
  EXPECT_FALSE(prior.add(at(1.1, std::numeric_limits<double>::infinity(), 0.0)));
  EXPECT_EQ(prior.rejected(), 2u);
}

}  // namespace
}  // namespace uavslam
