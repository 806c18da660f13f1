#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "SimTestHelpers.hpp"
#include "sim/World.hpp"

namespace uavslam::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTolerance = 1e-9;

// The empty 10 x 8 x 3 room with one box and one cylinder (z 0.5 .. 2) in it.
World furnished_room() {
  WorldSpec spec = testing::empty_room();
  spec.boxes.push_back({Vec3(6.0, 1.0, 0.0), Vec3(7.0, 3.0, 1.0)});
  Cylinder cylinder;
  cylinder.center = Eigen::Vector2d(3.0, 6.0);
  cylinder.radius = 0.5;
  cylinder.z0 = 0.5;
  cylinder.z1 = 2.0;
  spec.cylinders.push_back(cylinder);
  return World(spec);
}

// The empty room with a round wall of radius 3 about (5, 4), open from 150 to 210 degrees (its
// door faces -x), 0 to 2.5 m high.
World round_hall() {
  WorldSpec spec = testing::empty_room();
  ArcWall arc;
  arc.center = Eigen::Vector2d(5.0, 4.0);
  arc.radius = 3.0;
  arc.from_deg = -150.0;
  arc.to_deg = 150.0;
  arc.z0 = 0.0;
  arc.z1 = 2.5;
  spec.arcs.push_back(arc);
  return World(spec);
}

TEST(World, ARoundWallIsHitFromInsideAndOutsideButNotThroughItsDoor) {
  const World world = round_hall();
  const Vec3 centre(5.0, 4.0, 1.0);
  EXPECT_NEAR(world.cast_ray(centre, Vec3::UnitX(), 30.0, 0.0), 3.0, kTolerance);
  EXPECT_NEAR(world.cast_ray(centre, Vec3::UnitY(), 30.0, 0.0), 3.0, kTolerance);
  const Vec3 diagonal = Vec3(1.0, 1.0, 0.0).normalized();
  EXPECT_NEAR(world.cast_ray(centre, diagonal, 30.0, 0.0), 3.0, kTolerance);
  // Out through the door to the room's west wall, 5 m away.
  EXPECT_NEAR(world.cast_ray(centre, -Vec3::UnitX(), 30.0, 0.0), 5.0, kTolerance);
  // From outside, in the room's east part: the wall's outer side.
  EXPECT_NEAR(world.cast_ray(Vec3(9.5, 4.0, 1.0), -Vec3::UnitX(), 30.0, 0.0), 1.5, kTolerance);
  // Over the wall's top: the ceiling.
  EXPECT_NEAR(world.cast_ray(Vec3(5.0, 4.0, 2.0), Vec3(1.0, 0.0, 1.0).normalized(), 30.0, 0.0),
              std::sqrt(2.0), kTolerance);
  // Beyond max_range: nothing.
  EXPECT_EQ(world.cast_ray(centre, Vec3::UnitX(), 2.0, 0.0), kInf);
}

TEST(World, TheDistanceToARoundWallIsToItsCircleOrItsNearerEnd) {
  const World world = round_hall();
  EXPECT_NEAR(world.distance_to_nearest_obstacle(Vec3(5.0, 4.0, 1.0)), 3.0, kTolerance);
  EXPECT_NEAR(world.distance_to_nearest_obstacle(Vec3(9.0, 4.0, 1.0)), 1.0, kTolerance);
  // In the door: the nearer end, at 150 degrees.
  const Vec3 end(5.0 + 3.0 * std::cos(150.0 * M_PI / 180.0),
                 4.0 + 3.0 * std::sin(150.0 * M_PI / 180.0), 1.0);
  EXPECT_NEAR(world.distance_to_nearest_obstacle(Vec3(2.0, 4.0, 1.0)),
              (end - Vec3(2.0, 4.0, 1.0)).norm(), kTolerance);
  EXPECT_TRUE(world.is_free(Vec3(5.0, 4.0, 1.0)));
}

TEST(World, RayFromInsideHitsEachFaceOfTheRoom) {
  const World world(testing::empty_room());
  const Vec3 origin(2.0, 3.0, 1.0);
  EXPECT_NEAR(world.cast_ray(origin, Vec3::UnitX(), 30.0, 0.0), 8.0, kTolerance);
  EXPECT_NEAR(world.cast_ray(origin, -Vec3::UnitX(), 30.0, 0.0), 2.0, kTolerance);
  EXPECT_NEAR(world.cast_ray(origin, Vec3::UnitY(), 30.0, 0.0), 5.0, kTolerance);
  EXPECT_NEAR(world.cast_ray(origin, -Vec3::UnitY(), 30.0, 0.0), 3.0, kTolerance);
  EXPECT_NEAR(world.cast_ray(origin, Vec3::UnitZ(), 30.0, 0.0), 2.0, kTolerance);
  EXPECT_NEAR(world.cast_ray(origin, -Vec3::UnitZ(), 30.0, 0.0), 1.0, kTolerance);
}

TEST(World, DiagonalRayHitsTheNearerFace) {
  const World world(testing::empty_room());
  const Vec3 direction = Vec3(1.0, 1.0, 0.0).normalized();
  // From (2, 3): the wall y = 8 is 5 m away along y, the wall x = 10 is 8 m away along x.
  EXPECT_NEAR(world.cast_ray(Vec3(2.0, 3.0, 1.0), direction, 30.0, 0.0), 5.0 * std::sqrt(2.0),
              kTolerance);
}

TEST(World, SurfaceBeyondMaxRangeIsAMiss) {
  const World world(testing::empty_room());
  EXPECT_EQ(world.cast_ray(Vec3(2.0, 3.0, 1.0), Vec3::UnitX(), 7.9, 0.0), kInf);
  EXPECT_NEAR(world.cast_ray(Vec3(2.0, 3.0, 1.0), Vec3::UnitX(), 8.0, 0.0), 8.0, kTolerance);
}

TEST(World, RayHitsTheFrontFaceOfABox) {
  const World world = furnished_room();
  EXPECT_NEAR(world.cast_ray(Vec3(2.0, 2.0, 0.5), Vec3::UnitX(), 30.0, 0.0), 4.0, kTolerance);
  // From above: the top face at z = 1.
  EXPECT_NEAR(world.cast_ray(Vec3(6.5, 2.0, 2.5), -Vec3::UnitZ(), 30.0, 0.0), 1.5, kTolerance);
}

TEST(World, HorizontalRayPassingOverABoxHitsTheWall) {
  const World world = furnished_room();
  EXPECT_NEAR(world.cast_ray(Vec3(2.0, 2.0, 1.5), Vec3::UnitX(), 30.0, 0.0), 8.0, kTolerance);
}

TEST(World, RayHitsTheSideOfACylinder) {
  const World world = furnished_room();
  EXPECT_NEAR(world.cast_ray(Vec3(0.5, 6.0, 1.0), Vec3::UnitX(), 30.0, 0.0), 2.0, kTolerance);
  // Off the axis by 0.3 m: the side is at x = 3 - sqrt(0.5^2 - 0.3^2) = 2.6.
  EXPECT_NEAR(world.cast_ray(Vec3(0.5, 6.3, 1.0), Vec3::UnitX(), 30.0, 0.0), 2.1, kTolerance);
}

TEST(World, RayHitsTheCapsOfACylinder) {
  const World world = furnished_room();
  EXPECT_NEAR(world.cast_ray(Vec3(3.2, 6.1, 2.9), -Vec3::UnitZ(), 30.0, 0.0), 0.9, kTolerance);
  EXPECT_NEAR(world.cast_ray(Vec3(3.2, 6.1, 0.1), Vec3::UnitZ(), 30.0, 0.0), 0.4, kTolerance);
}

TEST(World, RayPassingBesideACylinderHitsTheWall) {
  const World world = furnished_room();
  EXPECT_NEAR(world.cast_ray(Vec3(0.5, 6.6, 1.0), Vec3::UnitX(), 30.0, 0.0), 9.5, kTolerance);
  // Above its top the cylinder is no obstacle either.
  EXPECT_NEAR(world.cast_ray(Vec3(0.5, 6.0, 2.5), Vec3::UnitX(), 30.0, 0.0), 9.5, kTolerance);
}

TEST(World, IsFreeInsideTheRoomOutsideObstacles) {
  const World world = furnished_room();
  EXPECT_TRUE(world.is_free(Vec3(1.0, 1.0, 1.0)));
  EXPECT_FALSE(world.is_free(Vec3(6.5, 2.0, 0.5)));   // in the box
  EXPECT_FALSE(world.is_free(Vec3(3.0, 6.2, 1.0)));   // in the cylinder
  EXPECT_TRUE(world.is_free(Vec3(3.0, 6.2, 2.5)));    // above the cylinder
  EXPECT_FALSE(world.is_free(Vec3(11.0, 1.0, 1.0)));  // outside the room
}

TEST(World, DistanceToNearestSurfaceIsExact) {
  const World world = furnished_room();
  EXPECT_NEAR(world.distance_to_nearest_surface(Vec3(5.0, 4.0, 1.5)), 1.5, kTolerance);  // ceiling
  EXPECT_NEAR(world.distance_to_nearest_surface(Vec3(5.5, 2.0, 0.5)), 0.5, kTolerance);  // box face
  // Diagonally off the box's top edge (x = 6, z = 1): sqrt(0.3^2 + 0.4^2).
  EXPECT_NEAR(world.distance_to_nearest_surface(Vec3(5.7, 2.0, 1.4)), 0.5, kTolerance);
  EXPECT_NEAR(world.distance_to_nearest_surface(Vec3(6.5, 2.0, 0.8)), 0.2, kTolerance);  // inside
  // Cylinder side, and diagonally off the rim of its top cap.
  EXPECT_NEAR(world.distance_to_nearest_surface(Vec3(3.0, 5.2, 1.0)), 0.3, kTolerance);
  EXPECT_NEAR(world.distance_to_nearest_surface(Vec3(3.0, 5.2, 2.4)), 0.5, kTolerance);
  EXPECT_NEAR(world.distance_to_nearest_obstacle(Vec3(5.0, 4.0, 1.5)), std::hypot(1.0, 1.0, 0.5),
              kTolerance);  // the box's corner (6, 3, 1)
}

}  // namespace
}  // namespace uavslam::sim
