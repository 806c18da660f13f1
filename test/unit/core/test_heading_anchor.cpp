// The map's heading anchored on the orientation source's: the mean of the first scans' heading
// corrections, turned back once.
#include <cmath>
#include <optional>

#include <gtest/gtest.h>

#include "core/extensions/HeadingAnchor.hpp"

namespace uavslam {
namespace {

TEST(HeadingAnchor, WithoutAWindowTheMapKeepsTheFirstSamplesHeading) {
  HeadingAnchor anchor(0.0);
  EXPECT_TRUE(anchor.settled());
  EXPECT_FALSE(anchor.add(0.0, 0.0));
  EXPECT_FALSE(anchor.add(5.0, 0.01));
  EXPECT_EQ(anchor.variance(), 0.0);
}

// The first sample was 4 mrad off (n_0), the later ones scatter by 1 mrad about the truth: each
// scan after the first measures c_k = n_0 - n_k, and the mean over the window is n_0.
TEST(HeadingAnchor, TurnsBackTheMeanOfTheWindowsCorrections) {
  HeadingAnchor anchor(1.0);
  EXPECT_FALSE(anchor.settled());
  EXPECT_FALSE(anchor.add(10.0, 0.0)) << "the founding scan only starts the clock";
  std::optional<double> turn;
  int k = 0;
  double t = 10.0;
  while (!turn) {
    ++k;
    t = 10.0 + 0.025 * k;
    ASSERT_LT(k, 50) << "no turn by the end of the window";
    turn = anchor.add(t, 0.004 + (k % 2 == 0 ? 0.001 : -0.001));
  }
  EXPECT_EQ(k, 40) << "at the first scan a whole window after the founding one";
  EXPECT_NEAR(*turn, -0.004, 1e-12);
  EXPECT_TRUE(anchor.settled());
  EXPECT_FALSE(anchor.add(t + 0.025, 0.5)) << "turned once only";
}

// Until the turn the map's heading may be off by one sample's noise (the corrections' scatter),
// after it by their mean's.
TEST(HeadingAnchor, SaysHowFarTheMapsHeadingMayBeFromTheSources) {
  HeadingAnchor anchor(1.0);
  anchor.add(0.0, 0.0);
  anchor.add(0.025, 0.001);
  EXPECT_EQ(anchor.variance(), 0.0) << "no scatter from one scan";
  std::optional<double> turn;
  int k = 1;
  while (!turn) {
    ++k;
    if (k == 21) {
      EXPECT_NEAR(anchor.variance(), 1e-6, 0.1e-6) << "one sample's";
    }
    turn = anchor.add(0.025 * k, k % 2 == 0 ? -0.001 : 0.001);
  }
  ASSERT_TRUE(turn);
  EXPECT_NEAR(*turn, 0.0, 1e-12);
  EXPECT_NEAR(anchor.variance(), 1e-6 / 40.0, 0.1e-6 / 40.0) << "the mean's, over 40 scans";
}

TEST(HeadingAnchor, CorrectionsAreWrappedBeforeTheyAreAveraged) {
  HeadingAnchor anchor(0.05);
  anchor.add(0.0, 0.0);
  anchor.add(0.025, 0.002 + 2.0 * M_PI);
  const std::optional<double> turn = anchor.add(0.05, 0.002 - 2.0 * M_PI);
  ASSERT_TRUE(turn);
  EXPECT_NEAR(*turn, -0.002, 1e-9);
}

}  // namespace
}  // namespace uavslam
