// The match against the motion prior: the Mahalanobis distance over the directions the scan fixed,
// and the scale MatchNoise learns from it.
#include <cmath>

#include <gtest/gtest.h>

#include "core/extensions/MatchNoise.hpp"
#include "core/extensions/PriorAgreement.hpp"

namespace uavslam {
namespace {

TEST(PriorAgreement, CountsOnlyTheDirectionsTheScanFixed) {
  // A corridor along x: the scan fixes y and z. A 3 m correction along x is no disagreement.
  Eigen::Matrix3d observed = Eigen::Matrix3d::Zero();
  observed(1, 1) = observed(2, 2) = 1.0;
  const Eigen::Matrix3d S = Eigen::Vector3d(1e-6, 1e-4, 4e-4).asDiagonal();
  const PriorDistance along = distance_from_prior(Vec3(3.0, 0.0, 0.0), observed, S);
  EXPECT_EQ(along.directions, 2);
  EXPECT_NEAR(along.sigmas, 0.0, 1e-9);
  // 2 cm across (sigma 1 cm) and 4 cm up (sigma 2 cm): sqrt(2^2 + 2^2).
  const PriorDistance across = distance_from_prior(Vec3(3.0, 0.02, 0.04), observed, S);
  EXPECT_NEAR(across.sigmas, std::sqrt(8.0), 1e-9);
}

TEST(PriorAgreement, ABlindScanMeasuresNothing) {
  const PriorDistance d =
      distance_from_prior(Vec3(1, 1, 1), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Identity());
  EXPECT_EQ(d.directions, 0);
  EXPECT_EQ(d.sigmas, 0.0);
}

TEST(PriorAgreement, NoSpreadMeansAnyCorrectionDisagrees) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_TRUE(std::isinf(distance_from_prior(Vec3(0.01, 0, 0), I, Eigen::Matrix3d::Zero()).sigmas));
  EXPECT_EQ(distance_from_prior(Vec3::Zero(), I, Eigen::Matrix3d::Zero()).sigmas, 0.0);
}

// Innovations that are 3 sigmas where 1 was promised: the scale grows until they are not; matches
// better than promised never shrink it below the information's own covariance.
TEST(MatchNoise, LearnsHowMuchTooConfidentTheMatchesAre) {
  MatchNoise noise;
  EXPECT_EQ(noise.scale(), 1.0);
  for (int i = 0; i < 100; ++i) noise.add({0.1, 2});
  EXPECT_EQ(noise.scale(), 1.0);
  // The true innovation is 3 sigmas of the unscaled covariance over 2 directions (d^2 / m = 4.5):
  // each match's distance is measured with the scale learnt so far, so it settles at 4.5.
  for (int i = 0; i < 2000; ++i) noise.add({3.0 / std::sqrt(noise.scale()), 2});
  EXPECT_NEAR(noise.scale(), 4.5, 0.2);
  noise.add({INFINITY, 2});  // ignored
  noise.add({100.0, 0});     // nothing observed: ignored
  EXPECT_NEAR(noise.scale(), 4.5, 0.2);
}

}  // namespace
}  // namespace uavslam
