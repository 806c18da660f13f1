// The Freiburg benchmark metric (Kümmerle et al. 2009) on hand-computed cases, its file readers,
// and the benchmark's own relation files when the shared data folder is present.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "TempDirTest.hpp"
#include "eval/RelationMetric.hpp"
#include "io/RelationsFile.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using uavslam::eval::compare_to_relations;
using uavslam::eval::PlanarStamped;
using uavslam::eval::Relation;
using uavslam::eval::RelationErrors;

constexpr double kPi = 3.14159265358979323846;

// The true relation between two poses: pose a's inverse composed with pose b.
Relation relation_between(const PlanarStamped& a, const PlanarStamped& b) {
  const double c = std::cos(a.theta);
  const double s = std::sin(a.theta);
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  return {a.t, b.t, c * dx + s * dy, -s * dx + c * dy, std::remainder(b.theta - a.theta, 2 * kPi)};
}

std::vector<PlanarStamped> truth() {
  return {{10.0, 0.0, 0.0, 0.0},
          {11.0, 1.0, 0.0, 0.3},
          {12.5, 1.5, 2.0, 2.0},
          {30.0, -3.0, 1.0, -2.9},
          {31.0, -3.5, 0.5, 3.0}};
}

std::vector<Relation> relations_of(const std::vector<PlanarStamped>& poses) {
  std::vector<Relation> relations;
  for (std::size_t i = 0; i + 1 < poses.size(); ++i) {
    relations.push_back(relation_between(poses[i], poses[i + 1]));
  }
  relations.push_back(relation_between(poses.back(), poses.front()));  // t2 < t1, 21 s apart
  return relations;
}

TEST(RelationMetric, AnEstimateEqualToTheTruthScoresZero) {
  const RelationErrors e = compare_to_relations(truth(), relations_of(truth()));
  EXPECT_EQ(e.all.relations, 5u);
  EXPECT_EQ(e.all.unmatched, 0u);
  EXPECT_EQ(e.all.translation.count, 5u);
  EXPECT_NEAR(e.all.translation.max, 0.0, 1e-12);
  EXPECT_NEAR(e.all.rotation.max, 0.0, 1e-12);
}

TEST(RelationMetric, TheEstimateMayBeInAnyGlobalFrameAndAnyOrder) {
  std::vector<PlanarStamped> moved;
  const double turn = 1.1;
  for (const PlanarStamped& p : truth()) {
    moved.push_back({p.t, 5.0 + std::cos(turn) * p.x - std::sin(turn) * p.y,
                     -2.0 + std::sin(turn) * p.x + std::cos(turn) * p.y, p.theta + turn});
  }
  std::swap(moved[0], moved[3]);  // the logs' stamps are not monotonic either
  const RelationErrors e = compare_to_relations(moved, relations_of(truth()));
  EXPECT_EQ(e.all.unmatched, 0u);
  EXPECT_NEAR(e.all.translation.max, 0.0, 1e-9);
  EXPECT_NEAR(e.all.rotation.max, 0.0, 1e-9);
}

TEST(RelationMetric, ARelationIsTheMotionInTheFrameOfTheFirstPose) {
  // Facing +y at (1, 2), then 1 m further along +y: 1 m straight ahead in the first pose's frame.
  const std::vector<PlanarStamped> estimate = {{0.0, 1.0, 2.0, kPi / 2}, {1.0, 1.0, 3.0, kPi / 2}};
  const RelationErrors ahead = compare_to_relations(estimate, {{0.0, 1.0, 1.0, 0.0, 0.0}});
  EXPECT_NEAR(ahead.all.translation.mean, 0.0, 1e-12);
  // The same motion written in world axes is off by (1, -1) in the first pose's frame.
  const RelationErrors world = compare_to_relations(estimate, {{0.0, 1.0, 0.0, 1.0, 0.0}});
  EXPECT_NEAR(world.all.translation.mean, std::sqrt(2.0), 1e-12);
}

TEST(RelationMetric, AHeadingErrorAtTheFirstPoseTurnsTheWholeMotion) {
  // Truth: 1 m straight ahead, no turn. The estimate's first heading is 0.1 rad too large, so it
  // sees the second pose at -0.1 rad: error chord 2 sin(0.05), rotation 0.1 rad.
  const std::vector<PlanarStamped> estimate = {{0.0, 0.0, 0.0, 0.1}, {1.0, 1.0, 0.0, 0.0}};
  const RelationErrors e = compare_to_relations(estimate, {{0.0, 1.0, 1.0, 0.0, 0.0}});
  EXPECT_NEAR(e.all.translation.mean, 2.0 * std::sin(0.05), 1e-12);
  EXPECT_NEAR(e.all.rotation.mean, 0.1, 1e-12);
}

TEST(RelationMetric, RotationErrorsAreNormalisedAcrossPi) {
  const std::vector<PlanarStamped> estimate = {{0.0, 0.0, 0.0, 3.1}, {1.0, 0.0, 0.0, -3.1}};
  const RelationErrors e = compare_to_relations(estimate, {{0.0, 1.0, 0.0, 0.0, 0.0}});
  EXPECT_NEAR(e.all.rotation.mean, 2 * kPi - 6.2, 1e-12);
}

TEST(RelationMetric, MeanStdAndMaxOfAnOffsetInOnePose) {
  // Pose 1 is 0.3 m, 0.4 m off: both relations touching it are 0.5 m off, the third is exact.
  const std::vector<PlanarStamped> estimate = {
      {0.0, 0.0, 0.0, 0.0}, {1.0, 1.3, 0.4, 0.0}, {2.0, 2.0, 0.0, 0.0}, {3.0, 3.0, 0.0, 0.0}};
  const std::vector<Relation> relations = {
      {0.0, 1.0, 1.0, 0.0, 0.0}, {1.0, 2.0, 1.0, 0.0, 0.0}, {2.0, 3.0, 1.0, 0.0, 0.0}};
  const RelationErrors e = compare_to_relations(estimate, relations);
  EXPECT_NEAR(e.all.translation.mean, 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(e.all.translation.std_dev, std::sqrt(2.0) / 6.0, 1e-12);  // population std
  EXPECT_NEAR(e.all.translation.max, 0.5, 1e-12);
  EXPECT_NEAR(e.all.rotation.max, 0.0, 1e-12);
}

TEST(RelationMetric, TheShortSubsetHoldsRelationsUnderFiveSecondsEitherWay) {
  const std::vector<PlanarStamped> estimate = {
      {0.0, 0.0, 0.0, 0.0}, {4.9, 1.0, 0.0, 0.0}, {10.0, 2.0, 0.0, 0.0}};
  const std::vector<Relation> relations = {
      {0.0, 4.9, 1.0, 0.0, 0.0},    // short, exact
      {10.0, 4.9, -1.0, 0.0, 0.0},  // 5.1 s backwards: long, exact
      {4.9, 0.0, -1.0, 0.2, 0.0},   // short backwards, 0.2 m off
      {0.0, 10.0, 2.0, 0.0, 0.5}};  // long, 0.5 rad off
  const RelationErrors e = compare_to_relations(estimate, relations);
  EXPECT_EQ(e.all.relations, 4u);
  EXPECT_EQ(e.short_span.relations, 2u);
  EXPECT_NEAR(e.short_span.translation.mean, 0.1, 1e-12);
  EXPECT_NEAR(e.short_span.rotation.max, 0.0, 1e-12);
  EXPECT_NEAR(e.all.rotation.max, 0.5, 1e-12);
}

TEST(RelationMetric, RelationsWithoutAnEstimateAreCountedAsUnmatched) {
  const std::vector<PlanarStamped> estimate = {{0.0, 0.0, 0.0, 0.0}, {1.0, 1.0, 0.0, 0.0}};
  const std::vector<Relation> relations = {{0.0, 1.0, 1.0, 0.0, 0.0},
                                           {0.0, 2.0, 9.0, 0.0, 0.0},
                                           {1.00001, 1.0, 9.0, 0.0, 0.0},  // beyond 1e-6 s
                                           {0.0, 20.0, 9.0, 0.0, 0.0}};
  const RelationErrors e = compare_to_relations(estimate, relations);
  EXPECT_EQ(e.all.relations, 4u);
  EXPECT_EQ(e.all.unmatched, 3u);
  EXPECT_EQ(e.all.translation.count, 1u);
  EXPECT_NEAR(e.all.translation.max, 0.0, 1e-12);
  EXPECT_EQ(e.short_span.relations, 3u);
  EXPECT_EQ(e.short_span.unmatched, 2u);
  // Each relation listed in order, the unmatched ones without errors.
  ASSERT_EQ(e.each.size(), 4u);
  EXPECT_EQ(e.each[0].t2, 1.0);
  ASSERT_TRUE(e.each[0].translation);
  EXPECT_NEAR(*e.each[0].translation, 0.0, 1e-12);
  EXPECT_FALSE(e.each[1].translation);
  EXPECT_FALSE(e.each[2].rotation);
  EXPECT_EQ(e.each[3].t2, 20.0);
}

// Motions estimated relation by relation (the scans' own alignment) score as an estimate would:
// the error is the estimated motion against the true one, and a missing one is unmatched.
TEST(RelationMetric, MotionsEstimatedRelationByRelationScoreTheSameWay) {
  const std::vector<Relation> relations = relations_of(truth());
  std::vector<std::optional<Relation>> estimated(relations.begin(), relations.end());
  estimated[1]->x += 0.3;  // 1.5 s apart: a short one
  estimated[2].reset();    // 17.5 s apart
  const RelationErrors e = uavslam::eval::compare_relation_estimates(relations, estimated);
  EXPECT_EQ(e.all.relations, 5u);
  EXPECT_EQ(e.all.unmatched, 1u);
  EXPECT_NEAR(e.all.translation.max, 0.3, 1e-12);
  EXPECT_NEAR(e.all.translation.mean, 0.3 / 4, 1e-12);
  EXPECT_NEAR(e.all.rotation.max, 0.0, 1e-12);
  EXPECT_EQ(e.short_span.translation.count, 3u);
  EXPECT_NEAR(e.short_span.translation.mean, 0.1, 1e-12);
}

// The translation error split along and across the relation's own direction: an estimate that
// moved 0.9 m where the relation says 1 m, and 0.1 m to its left, is 0.1 m short and 0.1 m left,
// whichever way the relation points; a relation under 1 cm has no direction to split along.
TEST(RelationMetric, TheErrorIsSplitAlongAndAcrossTheRelation) {
  const std::vector<Relation> relations = {
      {0.0, 1.0, 1.0, 0.0, 0.0}, {1.0, 2.0, 0.0, -2.0, 0.5}, {2.0, 3.0, 0.005, 0.0, 1.0}};
  const std::vector<std::optional<Relation>> estimated = {Relation{0.0, 1.0, 0.9, 0.1, 0.0},
                                                          Relation{1.0, 2.0, 0.1, -1.9, 0.5},
                                                          Relation{2.0, 3.0, 0.0, 0.0, 1.0}};
  const RelationErrors e = uavslam::eval::compare_relation_estimates(relations, estimated);
  ASSERT_TRUE(e.each[0].along && e.each[0].across);
  EXPECT_NEAR(*e.each[0].along, -0.1, 1e-12);
  EXPECT_NEAR(*e.each[0].across, 0.1, 1e-12);
  EXPECT_NEAR(e.each[0].length, 1.0, 1e-12);
  ASSERT_TRUE(e.each[1].along && e.each[1].across);
  EXPECT_NEAR(*e.each[1].along, -0.1, 1e-12);
  EXPECT_NEAR(*e.each[1].across, 0.1, 1e-12);
  EXPECT_TRUE(e.each[2].translation);
  EXPECT_FALSE(e.each[2].along);
  EXPECT_FALSE(e.each[2].across);
}

using RelationFiles = uavslam::test::TempDirTest;

TEST_F(RelationFiles, StampsPrintedTheSameWayMatchExactly) {
  const std::string relations =
      write("r.relations",
            "# t1 t2 x y z roll pitch yaw\n\n"
            "976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000 0.000000 0.000000 "
            "-1.682210\n");
  const std::string estimate = write("e.txt",
                                     "976052911.885496 -0.056990 -0.128430 -1.682210  # t2\n"
                                     "976052905.167303 0 0 0\n");
  const std::vector<Relation> r = uavslam::io::read_relations(relations);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_DOUBLE_EQ(r[0].yaw, -1.682210);
  EXPECT_DOUBLE_EQ(r[0].y, -0.128430);
  const std::vector<PlanarStamped> e = uavslam::io::read_planar_estimate(estimate);
  ASSERT_EQ(e.size(), 2u);
  const RelationErrors errors = compare_to_relations(e, r);
  EXPECT_EQ(errors.all.unmatched, 0u);
  EXPECT_NEAR(errors.all.translation.max, 0.0, 1e-12);
}

TEST_F(RelationFiles, AMalformedLineIsNamed) {
  const std::string relations = write("r.relations", "1 2 0 0 0 0 0 0\n1 2 0 0 0 0 0\n");
  EXPECT_THAT([&] { uavslam::io::read_relations(relations); },
              ::testing::ThrowsMessage<uavslam::io::FileError>(HasSubstr(relations + ":2:")));
  const std::string estimate = write("e.txt", "# t x y theta\n1 0 0 nan\n");
  EXPECT_THAT([&] { uavslam::io::read_planar_estimate(estimate); },
              ::testing::ThrowsMessage<uavslam::io::FileError>(HasSubstr(estimate + ":2:")));
  const std::string words = write("w.txt", "1 0 zero 0\n");
  EXPECT_THAT([&] { uavslam::io::read_planar_estimate(words); },
              ::testing::ThrowsMessage<uavslam::io::FileError>(HasSubstr("'zero'")));
}

TEST_F(RelationFiles, AMissingFileIsNamed) {
  const std::string missing = (dir / "none.relations").string();
  EXPECT_THAT([&] { uavslam::io::read_relations(missing); },
              ::testing::ThrowsMessage<uavslam::io::FileError>(HasSubstr(missing)));
  EXPECT_THAT([&] { uavslam::io::read_planar_estimate(missing); },
              ::testing::ThrowsMessage<uavslam::io::FileError>(HasSubstr(missing)));
}

// Relations taken from one trajectory close every triangle; one relation moved by 0.1 m opens the
// triangles it is in by that much, whichever direction each relation is given in.
TEST(RelationClosures, ExactRelationsCloseAndAMovedOneOpensItsTriangles) {
  const std::vector<PlanarStamped> poses = truth();
  std::vector<Relation> relations{relation_between(poses[0], poses[1]),
                                  relation_between(poses[2], poses[1]),  // given backwards
                                  relation_between(poses[0], poses[2]),
                                  relation_between(poses[2], poses[3]),
                                  relation_between(poses[3], poses[4])};
  const auto exact = uavslam::eval::relation_triangle_closures(relations);
  EXPECT_EQ(exact.triangles, 1u);  // scans 0, 1, 2
  EXPECT_NEAR(exact.translation.max, 0.0, 1e-12);
  EXPECT_NEAR(exact.rotation.max, 0.0, 1e-12);
  EXPECT_EQ(exact.triangles_with_short_leg, 1u);

  relations[2].x += 0.1;  // 0 -> 2
  const auto moved = uavslam::eval::relation_triangle_closures(relations);
  EXPECT_NEAR(moved.translation.mean, 0.1, 1e-9);
  EXPECT_NEAR(moved.rotation.max, 0.0, 1e-12);
}

// The benchmark's own files, from the shared data folder next to the repository.
void expect_relation_file(const std::string& name, std::size_t count, std::size_t short_count) {
  const std::string path = std::string(UAVSLAM_SOURCE_DIR) + "/../shared/data/freiburg/" + name;
  if (!fs::exists(path)) GTEST_SKIP() << path << " is absent: the Freiburg data is not installed";
  const std::vector<Relation> relations = uavslam::io::read_relations(path);
  EXPECT_EQ(relations.size(), count);
  // With no estimate at all every relation is unmatched, and the short ones are those the data
  // README counts.
  const RelationErrors e = compare_to_relations({}, relations);
  EXPECT_EQ(e.all.unmatched, count);
  EXPECT_EQ(e.short_span.relations, short_count);
}

TEST(FreiburgRelations, IntelHas2984Relations) {
  expect_relation_file("intel.relations", 2984, 1732);
}

TEST(FreiburgRelations, Fr079Has1685Relations) {
  expect_relation_file("fr079.relations", 1685, 984);
}

}  // namespace
