#include <cmath>

#include <gtest/gtest.h>

#include "core/WorldMap.hpp"
#include "core/extensions/PlanarCorrection.hpp"
#include "core/extensions/SurfaceNormals.hpp"

namespace uavslam {
namespace {

// Map points d on the walls of a 6 m x 4 m room (every 0.1 m); the scan is the same points seen
// from `body`, turned by `yaw` about it and moved by `shift`.
Correspondences room_pairs(const Vec3& body, double yaw, const Vec3& shift, bool with_normals) {
  Correspondences pairs;
  const Eigen::AngleAxisd turn(yaw, Vec3::UnitZ());
  const auto add = [&](const Vec3& d, const Vec3& normal) {
    pairs.map.push_back(d);
    pairs.scan.push_back(turn * (d - body) + body + shift);
    pairs.weights.emplace_back(1.0, 1.0, 0.0);
    if (with_normals) pairs.normals.push_back(normal);
  };
  for (double x = 0.0; x <= 6.0; x += 0.1) {
    add(Vec3(x, 0, 0), Vec3(0, 1, 0));
    add(Vec3(x, 4, 0), Vec3(0, -1, 0));
  }
  for (double y = 0.1; y < 4.0; y += 0.1) {
    add(Vec3(0, y, 0), Vec3(1, 0, 0));
    add(Vec3(6, y, 0), Vec3(-1, 0, 0));
  }
  return pairs;
}

// The ICP's loop in miniature: pairs stay as they are (known correspondences), the correction
// accumulates. Returns the total correction.
PlanarCorrection iterate(Correspondences pairs, const Vec3& body, bool estimate_yaw,
                         double prior_weight, int iterations) {
  PlanarCorrection total;
  Vec3 at = body;
  for (int k = 0; k < iterations; ++k) {
    const PlanarCorrection c = best_correction(pairs, at, {estimate_yaw, prior_weight, 0.0}, total);
    apply_correction(pairs.scan, at, c);
    at += c.translation;
    total.yaw += c.yaw;
    total.translation += c.translation;
  }
  return total;
}

TEST(PlanarCorrection, PointToPointRecoversAYawAndAShift) {
  const Vec3 body(2.0, 1.5, 0.0);
  const Correspondences pairs = room_pairs(body, 0.05, Vec3(0.08, -0.04, 0), false);
  const PlanarCorrection c = iterate(pairs, body, true, 0.0, 5);
  // Undoing m = R(yaw)(d - p) + p + s about p: d = R(-yaw)(m - p) + p - R(-yaw) s.
  const Vec3 expected = -(Eigen::AngleAxisd(-0.05, Vec3::UnitZ()) * Vec3(0.08, -0.04, 0));
  EXPECT_NEAR(c.yaw, -0.05, 1e-9);
  EXPECT_NEAR(c.translation.x(), expected.x(), 1e-9);
  EXPECT_NEAR(c.translation.y(), expected.y(), 1e-9);
}

TEST(PlanarCorrection, PointToLineRecoversAYawAndAShift) {
  const Vec3 body(4.0, 1.0, 0.0);
  const Correspondences pairs = room_pairs(body, -0.03, Vec3(-0.05, 0.07, 0), true);
  const PlanarCorrection c = iterate(pairs, body, true, 0.0, 5);
  const Vec3 expected = -(Eigen::AngleAxisd(0.03, Vec3::UnitZ()) * Vec3(-0.05, 0.07, 0));
  EXPECT_NEAR(c.yaw, 0.03, 1e-6);
  EXPECT_NEAR(c.translation.x(), expected.x(), 1e-6);
  EXPECT_NEAR(c.translation.y(), expected.y(), 1e-6);
}

TEST(PlanarCorrection, WithoutYawOnlyTheTranslationMoves) {
  const Vec3 body(3.0, 2.0, 0.0);
  const Correspondences pairs = room_pairs(body, 0.0, Vec3(0.1, 0.02, 0), true);
  const PlanarCorrection c = best_correction(pairs, body, {false, 0.0, 0.0});
  EXPECT_EQ(c.yaw, 0.0);
  EXPECT_NEAR(c.translation.x(), -0.1, 1e-9);
  EXPECT_NEAR(c.translation.y(), -0.02, 1e-9);
}

// A corridor along x: every wall normal is along y, so point-to-line pairs say nothing about x.
// The prior keeps x at the predicted start instead of letting noise decide it.
TEST(PlanarCorrection, ThePriorHoldsWhatTheScanCannotSee) {
  Correspondences corridor;
  for (double x = 0.0; x <= 10.0; x += 0.1) {
    for (const double y : {0.0, 2.0}) {
      corridor.map.emplace_back(x, y, 0.0);
      corridor.scan.emplace_back(x, y + 0.05, 0.0);
      corridor.weights.emplace_back(1.0, 1.0, 0.0);
      corridor.normals.emplace_back(0.0, y == 0.0 ? 1.0 : -1.0, 0.0);
    }
  }
  PlanarCorrection so_far;
  so_far.translation = Vec3(0.2, 0.0, 0.0);  // the ICP had wandered 0.2 m along the corridor
  const PlanarCorrection c = best_correction(corridor, Vec3(5, 1, 0), {false, 0.01, 0.0}, so_far);
  EXPECT_NEAR(c.translation.y(), -0.05, 1e-3);
  EXPECT_NEAR(c.translation.x(), -0.2, 1e-6) << "back to the start along the unseen axis";
}

TEST(PlanarCorrection, VerticalPairsGiveTheHeightAsTheSeedDoes) {
  Correspondences pairs;
  pairs.scan = {Vec3(0, 0, -1.0), Vec3(1, 0, -1.2)};
  pairs.map = {Vec3(0, 0, -1.3), Vec3(1, 0, -1.3)};
  pairs.weights = {Vec3(0, 0, 1), Vec3(0, 0, 1)};
  EXPECT_NEAR(best_correction(pairs, Vec3::Zero(), {true, 0.0, 0.0}).translation.z(), -0.2, 1e-12);
}

TEST(SurfaceNormals, PointsAlongAWallGetItsNormalAndACornerNone) {
  Points points;
  for (int i = 0; i < 10; ++i) points.emplace_back(1.0 + 0.05 * i, 2.0, 0.0);  // wall y = 2
  points.emplace_back(1.45, 2.05, 0.0);                                        // corner turns
  for (int i = 1; i < 10; ++i) points.emplace_back(1.45, 2.0 + 0.05 * (i + 1), 0.0);
  const std::vector<Vec3> normals =
      estimate_normals(points, std::vector<bool>(points.size(), false));
  ASSERT_EQ(normals.size(), points.size());
  EXPECT_NEAR(std::abs(normals[3].y()), 1.0, 1e-9);
  EXPECT_NEAR(normals[3].x(), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(normals[15].x()), 1.0, 1e-9);
  EXPECT_TRUE(normals[9].isZero()) << "the corner's neighbours are on two walls";
}

TEST(SurfaceNormals, AGapOrAVerticalBeamLeavesNoNormal) {
  const Points points = {Vec3(0, 0, 0), Vec3(0.05, 0, 0), Vec3(3, 1, 0), Vec3(3.05, 1, 0),
                         Vec3(3.1, 1, 0)};
  const std::vector<Vec3> normals = estimate_normals(points, {false, false, false, false, true});
  EXPECT_TRUE(normals[0].isZero()) << "two points on this side of the gap are not a line";
  EXPECT_TRUE(normals[4].isZero()) << "a floor beam";
  EXPECT_TRUE(normals[3].isZero()) << "only two level points near it";
}

WorldMap exact_map(double min_spacing) {
  SlamConfig::NearestNeighbour nn;
  nn.index = IndexKind::Exact;
  return WorldMap(make_nearest_neighbour_index(nn), min_spacing);
}

TEST(WorldMap, KeepsEveryPointWithoutASpacingAsTheSeed) {
  WorldMap map = exact_map(0.0);
  map.add_points({Vec3(0, 0, 0), Vec3(1, 0, 0)});
  EXPECT_EQ(map.add_points({Vec3(0.01, 0, 0)}).size(), 1u);
  EXPECT_EQ(map.size(), 3u);
  EXPECT_TRUE(map.normals().empty());
}

TEST(WorldMap, AddsOnlyPointsAwayFromTheMapWithTheirNormals) {
  WorldMap map = exact_map(0.1);
  map.add_points({Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(0, 1, 0), Vec3(0, 1, 0)});
  const Points added = map.add_points({Vec3(0.05, 0, 0), Vec3(0.5, 0, 0), Vec3(1.0, 0.2, 0)},
                                      {Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, -1, 0)});
  ASSERT_EQ(added.size(), 2u);
  EXPECT_EQ(added[0], Vec3(0.5, 0, 0));
  EXPECT_EQ(map.size(), 4u);
  ASSERT_EQ(map.normals().size(), 4u);
  EXPECT_EQ(map.normals()[2], Vec3(1, 0, 0));
  EXPECT_EQ(map.normals()[3], Vec3(0, -1, 0));
}

}  // namespace
}  // namespace uavslam
