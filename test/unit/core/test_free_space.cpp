#include <cmath>

#include <gtest/gtest.h>

#include "core/extensions/FreeSpace.hpp"

namespace uavslam {
namespace {

constexpr double kPi = 3.14159265358979323846;

// 0.1 m cells, beams mark free space up to 10 m, two crossings make a cell empty, 10 s memory,
// 0.2 m margin (the pairing gate).
FreeSpace free_space() {
  return FreeSpace(0.1, 10.0, 2, 10.0, 0.2);
}

// One beam per degree over +-40 degrees from `sensor`, ending on the wall x = wall_x, or on a
// pillar (`half_width` either side of `pillar` across the beams) where one stands in the way.
Points returns_from(const Vec3& sensor, double wall_x, const Vec3* pillar = nullptr,
                    double half_width = 0.1) {
  Points points;
  for (int deg = -40; deg <= 40; ++deg) {
    const Vec3 dir(std::cos(deg * kPi / 180.0), std::sin(deg * kPi / 180.0), 0.0);
    double range = (wall_x - sensor.x()) / dir.x();
    if (pillar != nullptr) {
      const Vec3 to = *pillar - sensor;
      const double along = to.dot(dir);
      if (along > 0.0 && (to - along * dir).norm() < half_width) range = along - 0.1;
    }
    points.push_back(sensor + range * dir);
  }
  return points;
}

TEST(FreeSpace, WhereTheBeamsPassedNothingStays) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  EXPECT_FALSE(space.moved_there(Vec3(2.0, 0.05, 0.3)));  // nothing seen yet
  // 2 m out, 1 degree beams are 3.5 cm apart: three cross each 0.1 m cell.
  space.add_scan(0.0, sensor, returns_from(sensor, 4.0));
  EXPECT_TRUE(space.moved_there(Vec3(2.0, 0.05, 0.3)));
  EXPECT_FALSE(space.moved_there(Vec3(4.02, 0.05, 0.3)));  // the wall
  // The last half metre before a return is not freed: a beam grazing a wall runs along it.
  EXPECT_FALSE(space.moved_there(Vec3(3.7, 0.05, 0.3)));
  EXPECT_FALSE(space.moved_there(Vec3(-1.0, 0.05, 0.3)));  // behind the scanner: never seen
}

TEST(FreeSpace, ASurfaceWithinTheMarginKeepsAPoint) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  const Vec3 pillar(3.0, 0.0, 0.3);
  for (int k = 0; k < 3; ++k) space.add_scan(0.1 * k, sensor, returns_from(sensor, 6.0, &pillar));
  // Beside the pillar the beams went on to the wall; a point there within 0.2 m of the pillar's
  // face (its first sight a return: a surface) is the pillar a pose a little off placed there.
  EXPECT_FALSE(space.moved_there(Vec3(2.95, 0.22, 0.3)));
  EXPECT_TRUE(space.moved_there(Vec3(2.95, 0.6, 0.3)));
}

TEST(FreeSpace, WhatTheBeamsSawLongAgoIsForgotten) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  space.add_scan(0.0, sensor, returns_from(sensor, 4.0));
  space.add_scan(0.1, sensor, returns_from(sensor, 4.0));
  EXPECT_TRUE(space.moved_there(Vec3(2.0, 0.05, 0.3)));
  // 20 s later, from elsewhere: a place seen empty that long ago may be where a drifted map's
  // wall now is.
  const Vec3 elsewhere(0.0, 30.0, 0.3);
  space.add_scan(20.0, elsewhere, returns_from(elsewhere, 4.0));
  EXPECT_FALSE(space.moved_there(Vec3(2.0, 0.05, 0.3)));
}

TEST(FreeSpace, APlaceSomethingLeftIsEmptyAgain) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  const Vec3 pillar(3.0, 0.0, 0.3);
  space.add_scan(0.0, sensor, returns_from(sensor, 6.0, &pillar));  // first seen: a surface
  EXPECT_FALSE(space.moved_there(Vec3(2.95, 0.0, 0.3)));
  // It walked away: the beams cross its place, several times for the one scan that saw it.
  for (int k = 1; k <= 6; ++k) space.add_scan(0.1 * k, sensor, returns_from(sensor, 6.0));
  EXPECT_TRUE(space.moved_there(Vec3(2.95, 0.0, 0.3)));
}

TEST(FreeSpace, WhatIsSeenScanAfterScanIsASurface) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  const Vec3 pillar(3.0, 0.0, 0.3);
  for (int k = 0; k < 3; ++k) space.add_scan(0.1 * k, sensor, returns_from(sensor, 6.0));
  // A cart pushed in and left: seen where the beams passed, then seen there for half a second
  // (at the half second itself, either).
  for (int k = 3; k < 10; ++k) {
    space.add_scan(0.1 * k, sensor, returns_from(sensor, 6.0, &pillar));
    if (k == 8) continue;
    const bool settled = k > 8;
    EXPECT_EQ(space.moved_there(Vec3(2.85, 0.0, 0.3)), !settled) << "scan " << k;  // its face
  }
  // What came does not vouch for the space beside it, as what stood there from the first does (a
  // walker's trail, seen by a fast scanner, would): behind its face, seen empty before it came.
  EXPECT_TRUE(space.moved_there(Vec3(2.95, 0.0, 0.3)));
}

// The body, the scanner at its origin, 0.3 m up.
const Vec3 kBody(0.0, 0.0, 0.3);

// The scan as the pipeline holds it: world-oriented points about the body.
ProjectedScan projected(const Points& points) {
  ProjectedScan scan;
  for (const Vec3& p : points) {
    scan.points.push_back(p - kBody);
    scan.vertical.push_back(false);
  }
  return scan;
}

TEST(FreeSpace, ASmallThingWithSeveralPointsInFreeSpaceMovedAllOfIt) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  for (int k = 0; k < 3; ++k) space.add_scan(0.1 * k, sensor, returns_from(sensor, 6.0));
  // A person stepped in 3 m ahead: 0.5 m across, 9 beams, in the middle of the scan.
  const Vec3 person(3.0, 0.0, 0.3);
  ProjectedScan scan = projected(returns_from(sensor, 6.0, &person, 0.25));
  const std::vector<bool> moved = moved_points(scan, kBody, 0.0, space);
  std::size_t count = 0;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const bool on_person = std::abs(scan.points[i].x()) < 3.5;
    EXPECT_EQ(moved[i], on_person) << i;
    count += moved[i];
  }
  EXPECT_GE(count, 8u);
  EXPECT_EQ(set_aside_moving(scan, kBody, 0.0, space), count);
  EXPECT_EQ(scan.points.size(), scan.vertical.size());
  for (const Vec3& p : scan.points) EXPECT_NEAR(p.x(), 6.0, 1e-9);
}

TEST(FreeSpace, ALoneReturnOrALongSurfaceInFreeSpaceStays) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  for (int k = 0; k < 3; ++k) space.add_scan(0.1 * k, sensor, returns_from(sensor, 6.0));
  // A wall 3 m ahead where the beams saw 6 m (a door closed, or a pose turned a little off):
  // longer than anything that walks.
  ProjectedScan wall = projected(returns_from(sensor, 3.0));
  for (const bool moved : moved_points(wall, kBody, 0.0, space)) EXPECT_FALSE(moved);
  // One return in free space: noise, or a mixed pixel at an edge.
  ProjectedScan scan = projected(returns_from(sensor, 6.0));
  scan.points[40] = Vec3(3.0, 0.0, 0.0);
  for (const bool moved : moved_points(scan, kBody, 0.0, space)) EXPECT_FALSE(moved);
}

TEST(FreeSpace, WhatAFastScannerSeesForAMomentIsNoSurface) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  for (int k = 0; k < 3; ++k) space.add_scan(0.025 * k, sensor, returns_from(sensor, 6.0));
  // A 40 Hz scanner sees a person's flank in a cell for a dozen scans as they walk past it: not
  // yet half a second, so not a surface; the same cell held on is one.
  const Vec3 person(3.0, 0.0, 0.3);
  int k = 3;
  for (; k < 15; ++k) space.add_scan(0.025 * k, sensor, returns_from(sensor, 6.0, &person));
  EXPECT_TRUE(space.moved_there(Vec3(2.85, 0.0, 0.3)));
  for (; k < 25; ++k) space.add_scan(0.025 * k, sensor, returns_from(sensor, 6.0, &person));
  EXPECT_FALSE(space.moved_there(Vec3(2.85, 0.0, 0.3)));
}

TEST(FreeSpace, FloorAndCeilingBeamsAreNeitherFreeSpaceNorMoved) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  for (int k = 0; k < 3; ++k) space.add_scan(0.1 * k, sensor, returns_from(sensor, 6.0));
  // A UAV just off the ground: its down-looking beams strike the floor 0.2 m under the free space
  // its level beams crossed.
  ProjectedScan scan = projected(returns_from(sensor, 6.0));
  for (int i = 0; i < 5; ++i) {
    scan.points.push_back(Vec3(2.0 + 0.05 * i, 0.0, -0.2));
    scan.vertical.push_back(true);
  }
  EXPECT_EQ(level_points(scan).size(), scan.points.size() - 5);
  for (const bool moved : moved_points(scan, kBody, 0.0, space)) EXPECT_FALSE(moved);
  // The same points from level beams are a small thing in free space (a box on the floor).
  for (std::size_t i = scan.vertical.size() - 5; i < scan.vertical.size(); ++i) {
    scan.vertical[i] = false;
  }
  EXPECT_EQ(set_aside_moving(scan, kBody, 0.0, space), 5u);
}

TEST(FreeSpace, OnlyTheScannersSlabOfTheBuildingIsJudged) {
  FreeSpace space = free_space();
  // A UAV 1.5 m up: its level beams pass over a table whose top is at 0.8 m, which the same beams
  // see a moment later when the vehicle tilts.
  const Vec3 sensor(0.0, 0.0, 1.5);
  for (int k = 0; k < 3; ++k) space.add_scan(0.1 * k, sensor, returns_from(sensor, 6.0));
  EXPECT_TRUE(space.moved_there(Vec3(3.0, 0.05, 1.5)));
  EXPECT_TRUE(space.moved_there(Vec3(3.0, 0.05, 1.7)));  // a level beam, the vehicle tilted
  EXPECT_FALSE(space.moved_there(Vec3(3.0, 0.05, 0.8)));
  // Beams that leave the slab neither free space nor leave returns in it.
  for (int k = 3; k < 6; ++k) {
    space.add_scan(0.1 * k, sensor, {Vec3(3.0, 0.05, 0.8), Vec3(2.0, -2.0, 3.0)});
  }
  EXPECT_TRUE(space.moved_there(Vec3(3.0, 0.05, 1.5)));
}

TEST(FreeSpace, MovedWithTheMapItKnowsWhatItSawWhereTheMoveTookIt) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  for (int k = 0; k < 3; ++k) space.add_scan(0.1 * k, sensor, returns_from(sensor, 4.0));
  // A loop closed: the map, and the vehicle with it, moved 1 m along y and turned 2 degrees.
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.translate(Vec3(0.0, 1.0, 0.0));
  moved.rotate(Eigen::AngleAxisd(2.0 * kPi / 180.0, Vec3::UnitZ()));
  space.move(moved);
  EXPECT_TRUE(space.moved_there(moved * Vec3(2.0, 0.05, 0.3)));
  EXPECT_FALSE(space.moved_there(Vec3(2.0, -0.9, 0.3)));           // the move left it behind
  EXPECT_FALSE(space.moved_there(moved * Vec3(4.02, 0.05, 0.3)));  // the wall, moved
}

TEST(FreeSpace, ClearedItKnowsNothing) {
  FreeSpace space = free_space();
  const Vec3 sensor(0.0, 0.0, 0.3);
  for (int k = 0; k < 3; ++k) space.add_scan(0.1 * k, sensor, returns_from(sensor, 4.0));
  space.clear();
  EXPECT_FALSE(space.moved_there(Vec3(2.0, 0.05, 0.3)));
}

}  // namespace
}  // namespace uavslam
