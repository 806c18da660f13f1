// The match against the motion prior: the Mahalanobis distance over the directions the scan fixed,
// and the scale MatchNoise learns from it.
#include <cmath>
#include <random>

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

// The gate at 5 sigmas (match and prior each sure to 1 cm): a correction of 3 cm agrees, one of
// 20 cm does not. Three such in a row, each agreeing with the last, and the fourth is taken: the
// prior has drifted, not the scans.
TEST(PriorGate, AfterARunOfRefusalsThatAgreeWithEachOtherTheNextMatchOverrulesThePrior) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d sure = 1e-4 * I;
  const auto judge = [&](PriorGate& gate, const Vec3& correction) {
    return gate.judge(distance_from_prior(correction, I, 2.0 * sure), correction, I, sure);
  };
  using V = PriorGate::Verdict;
  PriorGate gate(5.0, 3);
  EXPECT_EQ(judge(gate, Vec3(0.03, 0, 0)), V::Agrees);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(judge(gate, Vec3(0.2 + 0.005 * i, 0, 0)), V::Rejected) << i;
  EXPECT_EQ(judge(gate, Vec3(0.215, 0, 0)), V::Overrules);
  // The run starts again after it: the next refusal is the first of a new one.
  EXPECT_EQ(judge(gate, Vec3(0.2, 0, 0)), V::Rejected);
  // A match that agrees ends a run.
  EXPECT_EQ(judge(gate, Vec3(0.2, 0, 0)), V::Rejected);
  EXPECT_EQ(judge(gate, Vec3(0.0, 0, 0)), V::Agrees);
  EXPECT_EQ(judge(gate, Vec3(0.2, 0, 0)), V::Rejected);
  EXPECT_EQ(judge(gate, Vec3(0.2, 0, 0)), V::Rejected);
  EXPECT_EQ(judge(gate, Vec3(0.2, 0, 0)), V::Rejected);
  EXPECT_EQ(judge(gate, Vec3(0.2, 0, 0)), V::Overrules);
}

// Wrong matches that scatter (each far from the prior and from the one before) never make a run.
TEST(PriorGate, ScatteredRefusalsNeverOverrule) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d sure = 1e-4 * I;
  PriorGate gate(5.0, 3);
  for (int i = 0; i < 20; ++i) {
    const Vec3 correction = i % 2 == 0 ? Vec3(0.2, 0, 0) : Vec3(0, -0.2, 0);
    EXPECT_EQ(gate.judge(distance_from_prior(correction, I, 2.0 * sure), correction, I, sure),
              PriorGate::Verdict::Rejected)
        << i;
  }
}

TEST(PriorGate, NoGateAgreesAlwaysAndNoOverruleRefusesForever) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Vec3 far(1.0, 0, 0);
  const PriorDistance distance = distance_from_prior(far, I, 1e-4 * I);
  PriorGate none(0.0, 3);
  EXPECT_EQ(none.judge(distance, far, I, 1e-4 * I), PriorGate::Verdict::Agrees);
  PriorGate forever(5.0, 0);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(forever.judge(distance, far, I, 1e-4 * I), PriorGate::Verdict::Rejected) << i;
  }
}

// Matches promised to 1 cm in every direction, whose corrections of the prediction really spread
// 3 cm horizontally and 1 cm vertically: the horizontal scale grows to 9 (3^2), the vertical one
// stays near 1; matches better than promised never shrink either below the information's own.
TEST(MatchNoise, LearnsHowMuchTooConfidentEachChannelIs) {
  const Eigen::Matrix3d promised = 1e-4 * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d observed = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d predicted = Eigen::Matrix3d::Zero();
  MatchNoise noise;
  EXPECT_EQ(noise.horizontal_scale(), 1.0);
  // Matches ten times better than they promise: the scales learn that too.
  for (int i = 0; i < 100; ++i) noise.add(Vec3(0.001, 0.001, 0.001), observed, promised, predicted);
  EXPECT_LT(noise.horizontal_scale(), 0.5);
  EXPECT_LT(noise.vertical_scale(), 0.5);

  std::mt19937 random(7);
  std::normal_distribution<double> horizontal(0.0, 0.03);
  std::normal_distribution<double> vertical(0.0, 0.01);
  for (int i = 0; i < 3000; ++i) {
    const Vec3 correction(horizontal(random), horizontal(random), vertical(random));
    noise.add(correction, observed, promised, predicted);
  }
  EXPECT_NEAR(noise.horizontal_scale(), 9.0, 2.0);
  EXPECT_NEAR(noise.vertical_scale(), 1.0, 0.4);
  const Eigen::Matrix3d scaled = noise.scaled(promised);
  EXPECT_NEAR(scaled(0, 0), noise.horizontal_scale() * 1e-4, 1e-12);
  EXPECT_NEAR(scaled(2, 2), noise.vertical_scale() * 1e-4, 1e-12);

  // A match and a prediction that both claim no spread: the distance is infinite, ignored.
  const double before = noise.horizontal_scale();
  noise.add(Vec3(0.1, 0.1, 0.0), observed, Eigen::Matrix3d::Zero(), predicted);
  EXPECT_EQ(noise.horizontal_scale(), before);
}

}  // namespace
}  // namespace uavslam
