// How far the map's heading walks per keyframe, learnt from the periodic heading checks: the
// persistent part of their disagreements, not the match's white yaw noise.
#include <gtest/gtest.h>

#include <random>

#include "core/extensions/HeadingDrift.hpp"

namespace uavslam {
namespace {

TEST(HeadingDrift, NothingIsLearntBeforeTwoChecks) {
  HeadingDrift drift;
  EXPECT_EQ(drift.variance_per_keyframe(), 0.0);
  drift.add_check(0.01);
  EXPECT_EQ(drift.variance_per_keyframe(), 0.0);
  drift.add_check(0.01);
  EXPECT_NEAR(drift.variance_per_keyframe(), 1e-4, 1e-12);
}

// A steady source: the checks see only the match's yaw noise (2 mrad, white); what reaches the
// map is under a hundredth of its variance.
TEST(HeadingDrift, WhiteNoiseOfTheChecksIsNoDrift) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.002);
  HeadingDrift drift;
  for (int k = 0; k < 2000; ++k) drift.add_check(noise(random));
  EXPECT_LT(drift.variance_per_keyframe(), 0.01 * 0.002 * 0.002);
}

// A drifting source: the heading stays off from the map by 5 mrad under the same noise; the
// drift's square comes out, the noise's does not.
TEST(HeadingDrift, APersistentDisagreementIsLearntWithoutTheNoise) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.002);
  HeadingDrift drift;
  for (int k = 0; k < 2000; ++k) drift.add_check(0.005 + noise(random));
  EXPECT_NEAR(drift.variance_per_keyframe(), 0.005 * 0.005, 0.15 * 0.005 * 0.005);
}

}  // namespace
}  // namespace uavslam
