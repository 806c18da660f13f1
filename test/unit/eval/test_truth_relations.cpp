#include <cmath>

#include <gtest/gtest.h>

#include "core/Angles.hpp"
#include "eval/TruthRelations.hpp"

namespace uavslam::eval {
namespace {

// Around a 10 m x 6 m rectangle counter-clockwise at 0.5 m/s, then along its first side again:
// a pose every 0.1 s, the heading along the way.
std::vector<PlanarStamped> lap_and_a_side() {
  const double corners[5][2] = {{0, 0}, {10, 0}, {10, 6}, {0, 6}, {0, 0}};
  std::vector<PlanarStamped> path;
  double t = 0.0;
  auto drive = [&](double x0, double y0, double x1, double y1) {
    const double heading = std::atan2(y1 - y0, x1 - x0);
    const int steps = static_cast<int>(std::hypot(x1 - x0, y1 - y0) / 0.05);
    for (int k = 0; k < steps; ++k) {
      const double s = static_cast<double>(k) / steps;
      path.push_back({t, x0 + s * (x1 - x0), y0 + s * (y1 - y0), heading});
      t += 0.1;
    }
  };
  for (int side = 0; side < 4; ++side) {
    drive(corners[side][0], corners[side][1], corners[side + 1][0], corners[side + 1][1]);
  }
  drive(0, 0, 10, 0);
  return path;
}

TEST(TruthRelations, TheShortRelationsAreOneStepAlongThePath) {
  const std::vector<PlanarStamped> path = lap_and_a_side();
  const std::vector<Relation> relations = relations_from_truth(path);
  std::size_t short_ones = 0;
  for (const Relation& r : relations) {
    if (r.t2 - r.t1 >= 5.0) continue;
    ++short_ones;
    const double step = std::hypot(r.x, r.y);
    EXPECT_TRUE(step >= 0.2 - 1e-9 || std::abs(r.yaw) >= 0.17) << r.t1;
    EXPECT_LT(step, 0.26) << r.t1;
  }
  // 42 m of path in steps of 0.2 m (0.25 m at the 0.05 m sampling)
  EXPECT_GT(short_ones, 150u);
}

TEST(TruthRelations, RevisitsRelateTheLastSideToTheFirst) {
  const std::vector<PlanarStamped> path = lap_and_a_side();
  std::size_t revisits = 0;
  for (const Relation& r : relations_from_truth(path)) {
    if (r.t2 - r.t1 < 30.0) continue;
    ++revisits;
    EXPECT_LE(std::hypot(r.x, r.y), 1.0);
    EXPECT_LE(std::abs(r.yaw), 0.8);
    EXPECT_LT(r.t1, 20.0);  // on the first side: the first visit
    EXPECT_GT(r.t2, 64.0);  // on the last: after the lap
  }
  EXPECT_GE(revisits, 3u);
}

TEST(TruthRelations, EachRelationIsTheMotionInTheFirstPosesFrame) {
  const std::vector<PlanarStamped> path = {{0.0, 1.0, 1.0, kPi / 2}, {1.0, 1.0, 1.5, kPi / 2}};
  const std::vector<Relation> relations = relations_from_truth(path);
  ASSERT_EQ(relations.size(), 1u);
  EXPECT_NEAR(relations[0].x, 0.5, 1e-12);  // forward, as the robot faces north
  EXPECT_NEAR(relations[0].y, 0.0, 1e-12);
  EXPECT_NEAR(relations[0].yaw, 0.0, 1e-12);
  EXPECT_TRUE(relations_from_truth({}).empty());
}

}  // namespace
}  // namespace uavslam::eval
