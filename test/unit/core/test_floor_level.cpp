// The height from the floor's level: the floor seen under the body (FloorBelow), and the level
// taken near take-off measuring the height wherever that floor is seen again (FloorLevel).
#include <cmath>
#include <optional>

#include <gtest/gtest.h>

#include "core/ScanProjection.hpp"
#include "core/extensions/FloorBelow.hpp"
#include "core/extensions/FloorLevel.hpp"

namespace uavslam {
namespace {

// 31 downward beams from `height` above the floor, their ranges off by -15 to +15 mm in steps of
// 1 mm (the median exact, the median absolute deviation 8 mm), and one level beam (a wall) that is
// no floor.
ProjectedScan over_floor(double height, int beams = 31) {
  ProjectedScan scan;
  for (int i = 0; i < beams; ++i) {
    scan.points.push_back({0.0, 0.02 * (i - beams / 2), -height + 0.001 * (i - beams / 2)});
    scan.vertical.push_back(true);
  }
  scan.points.push_back({3.0, 0.0, -0.5});
  scan.vertical.push_back(false);
  return scan;
}

FloorSighting sighting(double below, double variance = 1e-6) {
  return FloorSighting{below, variance, 30};
}

TEST(FloorBelow, IsTheMedianDepthOfTheDownwardBeams) {
  const std::optional<FloorSighting> floor = floor_below(over_floor(1.5));
  ASSERT_TRUE(floor);
  EXPECT_EQ(floor->beams, 31u);
  EXPECT_NEAR(floor->below, 1.5, 1e-12);
  // The median's variance: (pi / 2) (1.4826 MAD)^2 / n.
  const double sigma = 1.4826 * 0.008;
  EXPECT_NEAR(floor->variance, M_PI / 2.0 * sigma * sigma / 31.0, 1e-12);
}

TEST(FloorBelow, AFewBeamsOnACrateDoNotLiftTheFloor) {
  ProjectedScan scan = over_floor(1.5);
  // The five deepest beams on a crate 0.6 m high: the median moves five of the beams' 1 mm steps,
  // not towards the crate.
  for (std::size_t i = 0; i < 5; ++i) scan.points[i].z() = -0.9;
  const std::optional<FloorSighting> floor = floor_below(scan);
  ASSERT_TRUE(floor);
  EXPECT_NEAR(floor->below, 1.495, 1e-9);
}

TEST(FloorBelow, NeedsThreeDownwardBeams) {
  EXPECT_FALSE(floor_below(over_floor(1.5, 2)));
  EXPECT_FALSE(floor_below(over_floor(-1.0))) << "returns above the body: no floor";
}

// Over the window the level is the mean of z - below; afterwards that floor measures the height.
TEST(FloorLevel, TheLevelTakenNearTakeOffMeasuresTheHeightLater) {
  FloorLevel level(1.0, 0.1, 0.01);
  double t = 0.0;
  for (; t < 1.0; t += 0.025) {
    // On the ground, 0.3 m above a floor the map puts at 0.002 +- 0.002 m.
    const double z = 0.3 + (int(t * 40) % 2 == 0 ? 0.002 : 0.0);
    EXPECT_FALSE(level.add(t, z, sighting(0.3))) << "still taking the level at " << t;
  }
  EXPECT_NEAR(level.level(), 0.001, 1e-4);
  EXPECT_NEAR(level.level_variance(), 1e-6 / 40.0, 1e-8);
  // 60 s later the chained height says 1.58 m over the floor seen 1.5 m below: the same floor
  // (0.08 m from the level, under the gate), so the height is the level's plus what it sees.
  const std::optional<HeightFix> fix = level.add(60.0, 1.58, sighting(1.5, 4e-6));
  ASSERT_TRUE(fix);
  EXPECT_TRUE(level.settled());
  EXPECT_NEAR(fix->height, 1.501, 1e-4);
  EXPECT_NEAR(fix->variance, 4e-6 + 1e-4 + level.level_variance(), 1e-12);
}

// A floor farther from the level than the gate is not the floor taken off from (a step, a crate's
// top, another storey): no fix, and the level stays.
TEST(FloorLevel, AnotherLevelIsNotTakenForTheFloor) {
  FloorLevel level(1.0, 0.1, 0.01);
  for (double t = 0.0; t <= 1.0; t += 0.025) level.add(t, 0.3, sighting(0.3));
  EXPECT_FALSE(level.add(30.0, 1.5, sighting(0.9))) << "a crate 0.6 m high";
  EXPECT_FALSE(level.add(31.0, 1.5, sighting(1.38))) << "a step of 0.12 m";
  EXPECT_TRUE(level.add(32.0, 1.5, sighting(1.45)));
  EXPECT_NEAR(level.level(), 0.0, 1e-12);
}

TEST(FloorLevel, TheWindowStartsWithTheFirstFloorSeen) {
  FloorLevel level(1.0, 0.1, 0.01);
  EXPECT_FALSE(level.add(5.0, 0.3, sighting(0.3)));
  EXPECT_FALSE(level.add(5.9, 0.3, sighting(0.3)));
  EXPECT_FALSE(level.settled());
  EXPECT_TRUE(level.add(6.0, 0.3, sighting(0.3)));
}

}  // namespace
}  // namespace uavslam
