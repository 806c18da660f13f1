#include <limits>

#include <gtest/gtest.h>

#include "SimTestHelpers.hpp"
#include "sim/Walker.hpp"
#include "sim/World.hpp"

namespace uavslam::sim {
namespace {

constexpr double kTolerance = 1e-9;

// Along x from (2, 4) to (6, 4), then up to (6, 6): 6 m at 1 m/s, starting 1 m in.
Walker walker_along_an_l() {
  Walker walker;
  walker.path = {Eigen::Vector2d(2.0, 4.0), Eigen::Vector2d(6.0, 4.0), Eigen::Vector2d(6.0, 6.0)};
  walker.speed = 1.0;
  walker.start = 1.0;
  walker.radius = 0.25;
  walker.height = 1.8;
  return walker;
}

TEST(Walker, WalksThePathToItsEndAndBackOverAndOver) {
  const Walker walker = walker_along_an_l();
  const auto at = [&](double t) { return walker_at(walker, t).center; };
  EXPECT_TRUE(at(0.0).isApprox(Eigen::Vector2d(3.0, 4.0), kTolerance));   // start
  EXPECT_TRUE(at(4.0).isApprox(Eigen::Vector2d(6.0, 5.0), kTolerance));   // round the corner
  EXPECT_TRUE(at(5.0).isApprox(Eigen::Vector2d(6.0, 6.0), kTolerance));   // the end
  EXPECT_TRUE(at(7.0).isApprox(Eigen::Vector2d(6.0, 4.0), kTolerance));   // back round it
  EXPECT_TRUE(at(11.0).isApprox(Eigen::Vector2d(2.0, 4.0), kTolerance));  // the beginning
  EXPECT_TRUE(at(12.0).isApprox(at(0.0), kTolerance));                    // again
  const Cylinder body = walker_at(walker, 0.0);
  EXPECT_EQ(body.radius, 0.25);
  EXPECT_EQ(body.z0, 0.0);
  EXPECT_EQ(body.z1, 1.8);
}

TEST(Walker, TheScansSeeAPersonWhereTheyAreWhenTheBeamIsFired) {
  WorldSpec spec = testing::empty_room();  // 10 x 8 x 3
  spec.people.push_back(walker_along_an_l());
  const World world(spec);
  const Vec3 scanner(3.0, 1.0, 0.5);
  // At t = 0 the person stands at (3, 4), in the beam up the y axis; 3 s later at (6, 4).
  EXPECT_NEAR(world.cast_ray(scanner, Vec3::UnitY(), 30.0, 0.0), 2.75, kTolerance);
  EXPECT_NEAR(world.cast_ray(scanner, Vec3::UnitY(), 30.0, 3.0), 7.0, kTolerance);
  // Above their head the beam reaches the wall; the map's truth never holds them.
  EXPECT_NEAR(world.cast_ray(Vec3(3.0, 1.0, 2.0), Vec3::UnitY(), 30.0, 0.0), 7.0, kTolerance);
  EXPECT_TRUE(world.is_free(Vec3(3.0, 4.0, 0.5)));
  EXPECT_NEAR(world.distance_to_nearest_surface(Vec3(3.0, 4.5, 0.5)), 0.5, kTolerance);
  // A person walking through the scanner hides nothing from it.
  EXPECT_NEAR(world.cast_ray(Vec3(3.1, 4.0, 0.5), -Vec3::UnitY(), 30.0, 0.0), 4.0, kTolerance);
}

}  // namespace
}  // namespace uavslam::sim
