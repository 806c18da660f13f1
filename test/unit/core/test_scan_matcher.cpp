#include <gtest/gtest.h>

#include "SyntheticRoom.hpp"
#include "core/ScanMatcher.hpp"
#include "core/ScanProjection.hpp"

namespace uavslam {
namespace {

WorldMap exact_map(const Points& points) {
  SlamConfig::NearestNeighbour nn;
  nn.index = IndexKind::Exact;
  WorldMap map(make_nearest_neighbour_index(nn));
  map.add_points(points);
  return map;
}

ScanPoints uniform(const Points& points) {
  return weigh_points(points, std::vector<bool>(points.size(), false), false);
}

TEST(ScanMatcher, BestTranslationIsTheDifferenceOfTheMeans) {
  Correspondences pairs;
  pairs.map = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 2, 0)};
  for (const Vec3& d : pairs.map) pairs.scan.push_back(d + Vec3(0.3, -0.1, 0.05));
  pairs.weights.assign(3, Vec3::Ones());
  EXPECT_TRUE(best_translation(pairs).isApprox(Vec3(0.3, -0.1, 0.05), 1e-12));
  // Eq. 5.18 is zero at the best translation and the squared offset at t = 0.
  EXPECT_NEAR(error_function(pairs, Vec3(0.3, -0.1, 0.05)), 0.0, 1e-20);
  EXPECT_NEAR(error_function(pairs), 0.09 + 0.01 + 0.0025, 1e-12);
}

TEST(ScanMatcher, SplitAxesTakeLateralFromLevelBeamsAndHeightFromVerticalOnes) {
  const Points points = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, -1)};
  const ScanPoints split = weigh_points(points, {false, false, true}, true);
  EXPECT_EQ(split.weights[0], Vec3(1, 1, 0));
  EXPECT_EQ(split.weights[2], Vec3(0, 0, 1));
  Correspondences pairs;
  pairs.scan = points;
  // Level beams are off by (0.2, -0.1) laterally and 0.5 vertically (a tilted scan meets the wall
  // at another height); the floor beam is off by 0.3 in height and 0.4 along the floor.
  pairs.map = {Vec3(0.8, 0.1, -0.5), Vec3(-0.2, 1.1, 0.5), Vec3(0.4, 0, -1.3)};
  pairs.weights = split.weights;
  EXPECT_TRUE(best_translation(pairs).isApprox(Vec3(0.2, -0.1, 0.3), 1e-12))
      << best_translation(pairs).transpose();
  // Eq. 5.18 counts each pair on its own axes only.
  EXPECT_NEAR(error_function(pairs), (0.04 + 0.01 + 0.04 + 0.01 + 0.09) / 3.0, 1e-12);
  // No vertical beam: nothing informs z, so the height is left as it is.
  pairs.scan.pop_back();
  pairs.map.pop_back();
  pairs.weights.pop_back();
  EXPECT_EQ(best_translation(pairs).z(), 0.0);
}

TEST(ScanMatcher, ApplyTransformMovesEveryPoint) {
  Points points = {Vec3(1, 1, 1), Vec3(-1, 0, 2)};
  apply_transform(points, Vec3(0.5, 0, -1));
  EXPECT_TRUE(points[0].isApprox(Vec3(1.5, 1, 0)));
  EXPECT_TRUE(points[1].isApprox(Vec3(-0.5, 0, 1)));
}

TEST(ScanMatcher, FindNearestPointsLeavesOutDistantPairsWhenAsked) {
  const WorldMap map = exact_map({Vec3(0, 0, 0), Vec3(10, 0, 0)});
  const ScanPoints scan = uniform({Vec3(0.1, 0, 0), Vec3(5, 0, 0)});
  EXPECT_EQ(find_nearest_points(map, scan, 0.0).scan.size(), 2u);
  const Correspondences near = find_nearest_points(map, scan, 1.0);
  ASSERT_EQ(near.scan.size(), 1u);
  EXPECT_TRUE(near.map[0].isZero());
}

// Pairs whose map point has no wall normal count nothing across the wall (their x-y weights);
// one left with no weight at all is dropped, a floor beam's pair (z only) is kept.
TEST(ScanMatcher, APairWithoutAWallNormalCountsNothingHorizontally) {
  Correspondences pairs;
  const std::vector<Vec3> weights = {Vec3(1, 1, 0), Vec3(1, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
  const std::vector<Vec3> normals = {Vec3::UnitY(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  for (std::size_t i = 0; i < weights.size(); ++i) {
    pairs.scan.emplace_back(double(i), 0.0, 0.0);
    pairs.map.emplace_back(double(i), 0.1, 0.0);
    pairs.map_index.push_back(i);
    pairs.weights.push_back(weights[i]);
    pairs.normals.push_back(normals[i]);
  }
  drop_pairs_without_normal(pairs);
  ASSERT_EQ(pairs.scan.size(), 3u);
  EXPECT_EQ(pairs.map_index, (std::vector<std::size_t>{0, 2, 3}));
  EXPECT_EQ(pairs.weights[0], Vec3(1, 1, 0));
  EXPECT_EQ(pairs.weights[1], Vec3(0, 0, 1));
  EXPECT_EQ(pairs.weights[2], Vec3(0, 0, 1));
  EXPECT_EQ(pairs.normals.size(), 3u);
}

// A corner: one wall mapped with its normal, the other's map points without (seen too sparsely
// for a line), the scan's points on it 4 cm along from them. Counted point to point, those
// offsets pull the match along the second wall, across the first; refined on the lines alone, the
// first wall places the match where it is (the ICP before still counts them all).
TEST(ScanMatcher, TheRefinementOnTheLinesIsNotPulledAlongAWallByItsPoints) {
  Points map_points;
  std::vector<Vec3> map_normals;
  for (double x = 0.5; x <= 5.0; x += 0.05) {
    map_points.emplace_back(x, 0.0, 0.0);
    map_normals.push_back(Vec3::UnitY());
  }
  for (double y = 0.5; y <= 5.0; y += 0.2) {
    map_points.emplace_back(0.0, y, 0.0);
    map_normals.push_back(Vec3::Zero());
  }
  WorldMap map = exact_map({});
  map.add_points(map_points, map_normals);
  Points scan_points;
  for (double x = 0.525; x <= 5.0; x += 0.1) scan_points.emplace_back(x, 0.0, 0.0);
  for (double y = 0.54; y <= 5.0; y += 0.2) scan_points.emplace_back(0.0, y, 0.0);
  const ScanPoints scan =
      weigh_points(scan_points, std::vector<bool>(scan_points.size(), false), true);
  SlamConfig::Icp icp;
  icp.metric = IcpMetric::PointToLine;
  icp.max_correspondence_distance = 0.3;
  icp.robust_scale = 0.03;
  icp.refine_iterations = 5;
  const MatchResult counted = ScanMatcher(icp).match(map, scan, Vec3::Zero());
  icp.refine_lines_only = true;
  const MatchResult refined = ScanMatcher(icp).match(map, scan, Vec3::Zero());
  ASSERT_EQ(counted.outcome, ScanOutcome::Accepted) << to_string(counted.outcome);
  ASSERT_EQ(refined.outcome, ScanOutcome::Accepted) << to_string(refined.outcome);
  EXPECT_GT(std::abs(counted.position.y()), 0.005) << counted.position.transpose();
  EXPECT_LT(std::abs(refined.position.y()), 1e-6) << refined.position.transpose();
}

class MatchInRoom : public ::testing::Test {
 protected:
  test::SyntheticRoom room;
  Pose truth;
  WorldMap map = exact_map({});
  void SetUp() override {
    // The map: the room seen from two places, every scan point.
    for (const Vec3& at : {Vec3(4, 3.5, 1.5), Vec3(6, 4, 1.5)}) {
      Pose p;
      p.position = at;
      Points pts = project_scan(room.scan_at(p, 0.0), p.orientation).points;
      apply_transform(pts, at);
      map.add_points(pts);
    }
    truth.position = Vec3(5.0, 3.8, 1.5);
  }
  ScanPoints scan_points() const {
    return uniform(
        keep_every_kth(project_scan(room.scan_at(truth, 0.0), truth.orientation).points, 5));
  }
};

TEST_F(MatchInRoom, RecoversAKnownOffset) {
  SlamConfig::Icp icp;
  icp.iterations = 30;
  const MatchResult r =
      ScanMatcher(icp).match(map, scan_points(), truth.position + Vec3(0.12, -0.08, 0));
  EXPECT_EQ(r.outcome, ScanOutcome::Accepted) << to_string(r.outcome);
  EXPECT_LT((r.position - truth.position).head<2>().norm(), 0.02) << r.position.transpose();
  EXPECT_LT(r.error_after, r.error_before);
  EXPECT_EQ(r.iterations, 30);
  EXPECT_EQ(r.aligned.size(), scan_points().points.size());
}

// A fifth of the scan 8 cm off the walls (a person along a wall, a moved cabinet), inside the
// gate: the plain ICP splits the difference; the refinement settles on the walls that agree.
TEST_F(MatchInRoom, TheRobustRefinementSettlesOnThePairsThatAgree) {
  ScanPoints scan = scan_points();
  for (std::size_t i = 0; i < scan.points.size() / 5; ++i) {
    scan.points[i] += 0.08 * scan.points[i].normalized();  // 8 cm farther along the beam
  }
  SlamConfig::Icp icp;
  icp.iterations = 30;
  icp.stop_step = 1e-5;
  icp.max_correspondence_distance = 0.2;
  const Vec3 start = truth.position + Vec3(0.03, -0.02, 0);
  const MatchResult plain = ScanMatcher(icp).match(map, scan, start, true);
  icp.robust_scale = 0.02;
  icp.refine_iterations = 10;
  const MatchResult refined = ScanMatcher(icp).match(map, scan, start, true);
  ASSERT_EQ(plain.outcome, ScanOutcome::Accepted) << to_string(plain.outcome);
  ASSERT_EQ(refined.outcome, ScanOutcome::Accepted) << to_string(refined.outcome);
  const double plain_error = (plain.position - truth.position).head<2>().norm();
  const double refined_error = (refined.position - truth.position).head<2>().norm();
  EXPECT_GT(plain_error, 0.005);
  EXPECT_LT(refined_error, plain_error / 2) << plain_error;
}

TEST_F(MatchInRoom, DiscardsAnErroneouslyLargeTranslation) {
  SlamConfig::Icp icp;
  icp.iterations = 50;
  icp.max_translation = 0.05;
  icp.max_correspondence_distance = 0.0;
  const MatchResult r =
      ScanMatcher(icp).match(map, scan_points(), truth.position + Vec3(0.4, 0, 0));
  EXPECT_EQ(r.outcome, ScanOutcome::TranslationTooLarge);
}

TEST_F(MatchInRoom, SkipsAScanWhoseErrorAfterIsTooLarge) {
  SlamConfig::Icp icp;
  icp.max_error_after = 1e-9;
  const MatchResult r = ScanMatcher(icp).match(map, scan_points(), truth.position);
  EXPECT_EQ(r.outcome, ScanOutcome::ErrorTooLarge);
}

TEST_F(MatchInRoom, ReportsNoCorrespondencesAgainstAFarAwayMap) {
  SlamConfig::Icp icp;
  icp.max_correspondence_distance = 0.5;
  const MatchResult r = ScanMatcher(icp).match(map, scan_points(), Vec3(100, 100, 0));
  EXPECT_EQ(r.outcome, ScanOutcome::NoCorrespondences);
}

}  // namespace
}  // namespace uavslam
