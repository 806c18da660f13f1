#include <cmath>

#include <gtest/gtest.h>

#include "core/NearestNeighbourIndex.hpp"
#include "core/extensions/BlindDirectionSearch.hpp"

namespace uavslam {
namespace {

// Surfaces as points every 2 cm, each with its normal (facing the scanner, as SurfaceNormals
// orients them).
struct Surfaces {
  Points points;
  std::vector<Vec3> normals;

  void add(const Vec3& from, const Vec3& direction, double length, const Vec3& normal) {
    for (double s = 0.0; s <= length + 1e-9; s += 0.02) {
      points.push_back(from + s * direction);
      normals.push_back(normal);
    }
  }
  // A 2 m wide corridor along x (walls at y = -1 and 1, facing its middle) from x = 0 to 20.
  void add_corridor() {
    add(Vec3(0, -1, 0), Vec3::UnitX(), 20.0, Vec3::UnitY());
    add(Vec3(0, 1, 0), Vec3::UnitX(), 20.0, -Vec3::UnitY());
  }
  // A pilaster's face across the corridor at x, from the north wall 0.4 m in, facing -x (a
  // scanner coming from the west sees it).
  void add_jamb(double x) { add(Vec3(x, 0.6, 0), Vec3::UnitY(), 0.4, -Vec3::UnitX()); }

  WorldMap map() const {
    WorldMap map(make_nearest_neighbour_index(SlamConfig::NearestNeighbour{}));
    map.add_points(points, normals);
    return map;
  }
  // The scan as the prior places it: the points moved by `error` along x (and `height` up).
  ScanPoints scan(double error, double height = 0.0) const {
    ScanPoints scan;
    for (std::size_t i = 0; i < points.size(); ++i) {
      scan.points.push_back(points[i] + error * Vec3::UnitX() + height * Vec3::UnitZ());
      scan.weights.emplace_back(1.0, 1.0, 0.0);
      scan.normals.push_back(normals[i]);
    }
    return scan;
  }
};

// The corridor with one jamb at x = 8 (its points after the walls').
Surfaces corridor_with_jamb() {
  Surfaces world;
  world.add_corridor();
  world.add_jamb(8.0);
  return world;
}

TEST(BlindDirectionSearch, AStructureAcrossTheAxisFixesIt) {
  const Surfaces world = corridor_with_jamb();
  const WorldMap map = world.map();
  for (const double error : {0.3, -0.45, 0.0}) {
    const std::optional<DirectionFix> fix =
        search_blind_direction(map, world.scan(error), Vec3::UnitX(), {});
    ASSERT_TRUE(fix) << "error " << error;
    EXPECT_NEAR(fix->offset, -error, 1e-3);
    EXPECT_EQ(fix->map_points, 21u);            // the jamb's
    EXPECT_NEAR(fix->information, 21.0, 1e-9);  // each pair's (n . e)^2 = 1
    EXPECT_LT(fix->uniqueness, 0.5);
  }
}

TEST(BlindDirectionSearch, APlainCorridorGivesNoFix) {
  Surfaces world;
  world.add_corridor();
  EXPECT_FALSE(search_blind_direction(world.map(), world.scan(0.3), Vec3::UnitX(), {}));
}

// Two jambs 0.5 m apart in the map, the scan seeing one: either could be it.
TEST(BlindDirectionSearch, ALookAlikeWithinTheWindowGivesNoFix) {
  const Surfaces world = corridor_with_jamb();
  Surfaces mapped = world;
  mapped.add_jamb(8.5);
  const WorldMap map = mapped.map();
  EXPECT_FALSE(search_blind_direction(map, world.scan(0.2), Vec3::UnitX(), {}));
  // Beyond the window searched, the other is no candidate.
  BlindSearchOptions narrow;
  narrow.half_width = 0.25;
  const std::optional<DirectionFix> fix =
      search_blind_direction(map, world.scan(0.2), Vec3::UnitX(), narrow);
  ASSERT_TRUE(fix);
  EXPECT_NEAR(fix->offset, -0.2, 1e-3);
}

// The same face seen from the other side is another surface: a scan of a face towards +x does not
// pair with the map's face towards -x.
TEST(BlindDirectionSearch, AFaceDoesNotPairWithItsBack) {
  const Surfaces world = corridor_with_jamb();
  Surfaces seen = world;
  for (Vec3& n : seen.normals) {
    if (n.x() < -0.5) n = Vec3::UnitX();
  }
  EXPECT_FALSE(search_blind_direction(world.map(), seen.scan(0.3), Vec3::UnitX(), {}));
}

// Map points the caller rules out (a keyframe made while the direction was blind, placed no better
// than the vehicle) are no pair: the jamb they hold fixes nothing.
TEST(BlindDirectionSearch, AStructureOnlyUnplacedMapPointsHoldIsNotTaken) {
  Surfaces walls;
  walls.add_corridor();
  const std::size_t wall_points = walls.points.size();
  const Surfaces world = corridor_with_jamb();
  const WorldMap map = world.map();
  const MapPointFilter walls_only = [wall_points](std::size_t index) {
    return index < wall_points;
  };
  EXPECT_FALSE(search_blind_direction(map, world.scan(0.3), Vec3::UnitX(), {}, walls_only));
  const MapPointFilter every = [](std::size_t) { return true; };
  EXPECT_TRUE(search_blind_direction(map, world.scan(0.3), Vec3::UnitX(), {}, every));
}

// A jamb's face stands over the storey: the keyframe that holds it (the take-off's, mapped 1 m
// lower) fixes a scan flown higher, though a keyframe the caller rules out holds a copy of it
// nearer in 3D (at the scan's height, 10 cm off: made while the direction drifted).
TEST(BlindDirectionSearch, AJambMappedAtAnotherHeightFixesItThoughARuledOutCopyIsNearer) {
  const Surfaces world = corridor_with_jamb();
  Surfaces mapped = world;
  const std::size_t placed = mapped.points.size();
  Surfaces drifted;
  drifted.add_jamb(8.1);
  for (std::size_t i = 0; i < drifted.points.size(); ++i) {
    mapped.points.push_back(drifted.points[i] + Vec3::UnitZ());
    mapped.normals.push_back(drifted.normals[i]);
  }
  const MapPointFilter placed_only = [placed](std::size_t index) { return index < placed; };
  const std::optional<DirectionFix> fix =
      search_blind_direction(mapped.map(), world.scan(0.3, 1.0), Vec3::UnitX(), {}, placed_only);
  ASSERT_TRUE(fix);
  EXPECT_NEAR(fix->offset, -0.3, 1e-3);
  EXPECT_EQ(fix->map_points, 21u);  // the placed jamb's
}

}  // namespace
}  // namespace uavslam
