// The orientation source's heading drift, learnt from checks against map of known age: what the
// checks see over long spans is the drift; what they see over short ones is mostly their noise.
#include <gtest/gtest.h>

#include <random>

#include "core/extensions/HeadingRate.hpp"

namespace uavslam {
namespace {

constexpr double kPerMinute = 1.0 / 60.0;
constexpr double kDegree = 3.14159265358979 / 180.0;

// A source drifting 2 degrees a minute, nothing applied yet: each check disagrees by the drift
// over its span (plus 1.5 mrad of noise), spans of 1 to 60 s.
TEST(HeadingRate, ASteadyDriftIsLearntFromTheChecks) {
  const double drift = -2.0 * kDegree * kPerMinute;  // the rate the correction must follow
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 0.0015);
  std::uniform_real_distribution<double> span(1.0, 60.0);
  HeadingRate rate(5.0 * kDegree * kPerMinute);
  for (int k = 0; k < 400; ++k) {
    const double dt = span(random);
    rate.add_check(drift * dt + noise(random), dt, 0.0);
  }
  EXPECT_NEAR(rate.rate(), drift, 0.05 * std::abs(drift));
}

// What was applied over a span counts: the same drift, half of it already followed, the checks
// see the other half and the rate is the whole.
TEST(HeadingRate, WhatWasAppliedIsPartOfTheDrift) {
  const double drift = 1.0 * kDegree * kPerMinute;
  HeadingRate rate(5.0 * kDegree * kPerMinute);
  for (int k = 1; k <= 100; ++k) {
    const double dt = 0.5 * k;
    rate.add_check(0.5 * drift * dt, dt, 0.5 * drift * dt);
  }
  EXPECT_NEAR(rate.rate(), drift, 1e-3 * drift);
}

// A steady source: the checks' noise over like spans is no drift, however many of them.
TEST(HeadingRate, NoiseOverShortSpansIsNoDrift) {
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0.0, 0.0015);
  HeadingRate rate(5.0 * kDegree * kPerMinute);
  EXPECT_EQ(rate.rate(), 0.0);
  for (int k = 0; k < 2000; ++k) rate.add_check(noise(random), 0.5, 0.0);
  EXPECT_EQ(rate.rate(), 0.0);
}

// Fewer than 30 checks: not believed, however clear.
TEST(HeadingRate, AFewChecksAreNotBelieved) {
  const double drift = 2.0 * kDegree * kPerMinute;
  HeadingRate rate(5.0 * kDegree * kPerMinute);
  for (int k = 1; k < 30; ++k) rate.add_check(drift * k, double(k), 0.0);
  EXPECT_EQ(rate.rate(), 0.0);
  rate.add_check(drift * 30.0, 30.0, 0.0);
  EXPECT_NEAR(rate.rate(), drift, 1e-9);
}

// A heading off the map by a steady 2 mrad (under the check's tolerance, never corrected): the
// checks disagree by it whatever their span, an offset, not a drift; a drift on top is found.
TEST(HeadingRate, AnOffsetThatDoesNotGrowWithTheSpanIsNoDrift) {
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, 0.0015);
  std::uniform_real_distribution<double> span(1.0, 5.0);
  HeadingRate offset(5.0 * kDegree * kPerMinute);
  HeadingRate drifting(5.0 * kDegree * kPerMinute);
  const double drift = 2.0 * kDegree * kPerMinute;
  for (int k = 0; k < 400; ++k) {
    const double dt = span(random);
    offset.add_check(0.002 + noise(random), dt, 0.0);
    drifting.add_check(0.002 + drift * dt + noise(random), dt, 0.0);
  }
  EXPECT_EQ(offset.rate(), 0.0);
  EXPECT_NEAR(drifting.rate(), drift, 0.25 * drift);
}

// The keyframes made before the drift was learnt: each is turned by the drift since the first
// keyframe less what the correction had already taken of it when it was made.
TEST(HeadingRate, TheKeyframesTurnByTheDriftTheyWereNotCorrectedFor) {
  const double drift = 2.0 * kDegree * kPerMinute;
  HeadingRate rate(5.0 * kDegree * kPerMinute);
  const std::vector<double> stamps{5.0, 15.0, 35.0};
  const std::vector<double> corrections{0.01, 0.01, 0.01 + 10.0 * drift};
  for (double turn : rate.turns(stamps, corrections)) EXPECT_EQ(turn, 0.0);  // nothing learnt
  for (int k = 1; k <= 100; ++k) rate.add_check(drift * k, double(k), 0.0);
  ASSERT_NEAR(rate.rate(), drift, 1e-3 * drift);
  const std::vector<double> turns = rate.turns(stamps, corrections);
  ASSERT_EQ(turns.size(), 3u);
  EXPECT_NEAR(turns[0], 0.0, 1e-12);
  EXPECT_NEAR(turns[1], 10.0 * drift, 1e-3 * drift);
  EXPECT_NEAR(turns[2], 20.0 * drift, 1e-2 * drift);
}

// A rate the checks show at four standard errors is followed, but the map is not turned on it
// (five): noise at the right moment passes three now and then. Spans of 1..40 s, the checks
// alternating +-a about the drift's line: the standard error is about a / 73.
TEST(HeadingRate, TheMapIsTurnedOnlyOnAClearRate) {
  const double drift = 1e-4;  // rad/s
  const auto learnt = [drift](double a) {
    HeadingRate rate(5.0 * kDegree * kPerMinute);
    for (int k = 1; k <= 40; ++k) rate.add_check(drift * k + (k % 2 == 0 ? a : -a), k, 0.0);
    return rate;
  };
  const std::vector<double> stamps{0.0, 60.0};
  const std::vector<double> corrections{0.0, 0.0};
  const HeadingRate four = learnt(18.0 * drift);
  EXPECT_NE(four.rate(), 0.0);
  EXPECT_EQ(four.turns(stamps, corrections)[1], 0.0);
  const HeadingRate seven = learnt(10.0 * drift);
  EXPECT_NEAR(seven.turns(stamps, corrections)[1], 60.0 * seven.rate(), 1e-12);
}

TEST(HeadingRate, NothingIsLearntWithoutAPriorOrASpan) {
  HeadingRate off(0.0);
  HeadingRate on(5.0 * kDegree * kPerMinute);
  for (int k = 0; k < 100; ++k) {
    off.add_check(0.01, 30.0, 0.0);
    on.add_check(0.01, 0.0, 0.0);  // the check matched map made at its own time
  }
  EXPECT_EQ(off.rate(), 0.0);
  EXPECT_EQ(on.rate(), 0.0);
}

// What the map's covariance takes: the prior until a line can be fitted (three checks), then the
// line's rate however few standard errors, and a variance that shrinks as the checks add up (the
// early keyframes' heading is the surer for it).
TEST(HeadingRate, TheEstimateIsThePriorAtFirstThenTheLinesAsItTightens) {
  const double prior = 5.0 * kDegree * kPerMinute;
  const double drift = -2.0 * kDegree * kPerMinute;
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, 0.0015);
  HeadingRate rate(prior);
  EXPECT_EQ(rate.estimate().rate, 0.0);
  EXPECT_DOUBLE_EQ(rate.estimate().variance, prior * prior);
  double last = prior * prior;
  for (int k = 1; k <= 60; ++k) {
    const double dt = 1.0 + (k % 20);
    rate.add_check(drift * dt + noise(random), dt, 0.0);
    if (k == 2) {
      EXPECT_DOUBLE_EQ(rate.estimate().variance, prior * prior);
    }
    if (k == 10 || k == 60) {
      EXPECT_LT(rate.estimate().variance, 0.5 * last);
      last = rate.estimate().variance;
    }
  }
  EXPECT_EQ(rate.rate(), rate.estimate().rate);  // past 30 checks and three standard errors
  EXPECT_NEAR(rate.estimate().rate, drift, 4.0 * std::sqrt(rate.estimate().variance));
  // Without a prior nothing is followed, but the line still says how far the map may be turned.
  HeadingRate off(0.0);
  EXPECT_EQ(off.estimate().variance, 0.0);
  for (int k = 1; k <= 60; ++k) {
    const double dt = 1.0 + (k % 20);
    off.add_check(drift * dt + noise(random), dt, 0.0);
  }
  EXPECT_EQ(off.rate(), 0.0);
  EXPECT_NEAR(off.estimate().rate, drift, 4.0 * std::sqrt(off.estimate().variance));
  EXPECT_GT(off.estimate().variance, 0.0);
}

}  // namespace
}  // namespace uavslam
