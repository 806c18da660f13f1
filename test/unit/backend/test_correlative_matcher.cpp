#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "backend/CorrelativeMatcher.hpp"
#include "unit/backend/Walls2d.hpp"

namespace uavslam::backend {
namespace {

using test::add_box;
using test::add_wall;
using test::Points2;

// A 10 m x 7 m room with a partition and boxes placed without symmetry; its frame's origin is
// off the grid's lines so no point sits on a cell boundary.
Points2 asymmetric_room() {
  Points2 points;
  add_box(points, {0.013, 0.007}, {10.013, 7.007});
  add_wall(points, {4.013, 7.007}, {4.013, 4.807});  // a partition from the top wall
  add_box(points, {1.8, 1.1}, {2.5, 1.6});
  add_box(points, {6.6, 4.1}, {7.7, 4.5});
  add_box(points, {8.2, 0.9}, {8.5, 2.7});
  return points;
}

// A 20 m corridor along x, 2 m wide, with a door recessed 0.2 m into its left wall every 2 m:
// every stretch looks like the one 2 m further.
Points2 corridor() {
  Points2 points;
  add_wall(points, {-10, -1}, {10, -1});
  for (int k = -5; k < 5; ++k) {
    const double x = 2.0 * k + 1.0;  // a door centred at x, 0.9 m wide
    add_wall(points, {x - 1.0, 1}, {x - 0.45, 1});
    add_wall(points, {x - 0.45, 1}, {x - 0.45, 1.2});
    add_wall(points, {x - 0.45, 1.2}, {x + 0.45, 1.2});
    add_wall(points, {x + 0.45, 1.2}, {x + 0.45, 1});
    add_wall(points, {x + 0.45, 1}, {x + 1.0, 1});
  }
  return points;
}

// Reference points as seen from `pose` (x, y, yaw in the reference's frame), each moved along its
// ray by noise of `sigma` (m), keeping those within `range` of the pose.
Points2 seen_from(const Points2& reference, const Eigen::Vector3d& pose, double sigma,
                  double range = 1e9, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const Eigen::Rotation2Dd turn(pose.z());
  Points2 scan;
  for (const auto& p : reference) {
    const Eigen::Vector2d local = turn.inverse() * (p - pose.head<2>());
    if (local.norm() > range || local.norm() < 1e-6) continue;
    scan.push_back(local + noise(rng) * local.normalized());
  }
  return scan;
}

// Every other point: a keyframe's scan subsampled to about the grid's cell.
Points2 every_other(const Points2& points) {
  Points2 out;
  for (std::size_t i = 0; i < points.size(); i += 2) out.push_back(points[i]);
  return out;
}

TEST(CorrelativeMatcher, RecoversAKnownOffsetInARoom) {
  const Points2 room = asymmetric_room();
  const Eigen::Vector3d truth(0.62, -0.37, 0.21);
  const Points2 scan = every_other(seen_from(room, truth + Eigen::Vector3d(4, 3, 0), 0.01));
  CorrelativeMatcher matcher(room, CorrelativeMatcherConfig{});
  SearchWindow window;
  window.centre = Eigen::Vector3d(4, 3, 0);  // truth is (4.62, 2.63, 0.21)
  window.linear = 1.0;
  window.angular = 0.5;
  const CorrelativeMatch m = matcher.match(scan, window, 0.5);
  ASSERT_TRUE(m.found);
  const double cell = matcher.config().resolution;
  EXPECT_NEAR(m.pose.x(), 4.62, 1.5 * cell);
  EXPECT_NEAR(m.pose.y(), 2.63, 1.5 * cell);
  EXPECT_NEAR(m.pose.z(), 0.21, matcher.angular_step(scan) + 1e-9);
  EXPECT_GT(m.score, 0.8);
  EXPECT_NEAR(matcher.score(scan, m.pose), m.score, 1e-9);
}

// Scores every pose of the window's discretisation: centre + (dx, dy) cells, centre yaw + k steps.
// With `far_from`, only the look-alikes of that pose (CorrelativeMatcherConfig's ambiguity_*).
double brute_force_best(const CorrelativeMatcher& matcher, const Points2& scan,
                        const SearchWindow& w, const Eigen::Vector3d* far_from = nullptr) {
  const CorrelativeMatcherConfig& config = matcher.config();
  const double res = config.resolution;
  const double step = matcher.angular_step(scan);
  const int reach = static_cast<int>(std::floor(w.linear / res + 1e-9));
  const int turns = static_cast<int>(std::floor(w.angular / step + 1e-9));
  double best = -1.0;
  for (int k = -turns; k <= turns; ++k)
    for (int dx = -reach; dx <= reach; ++dx)
      for (int dy = -reach; dy <= reach; ++dy) {
        const Eigen::Vector3d pose(w.centre.x() + dx * res, w.centre.y() + dy * res,
                                   w.centre.z() + k * step);
        if (far_from) {
          const double turn = std::remainder(pose.z() - far_from->z(), 2 * M_PI);
          const double cells = (pose.head<2>() - far_from->head<2>()).norm() / res;
          if (std::abs(turn) < config.ambiguity_angle &&
              cells < config.ambiguity_radius / res - 1e-6)
            continue;
        }
        best = std::max(best, matcher.score(scan, pose));
      }
  return best;
}

TEST(CorrelativeMatcher, BranchAndBoundFindsTheBruteForceOptimum) {
  const Points2 room = asymmetric_room();
  const Eigen::Vector3d truth(3.3, 2.2, -0.4);
  Points2 scan = seen_from(room, truth, 0.02, 6.0, 11);
  Points2 sparse;  // a few hundred points keep the brute force short
  for (std::size_t i = 0; i < scan.size(); i += 7) sparse.push_back(scan[i]);
  for (int levels : {3, 7}) {
    CorrelativeMatcherConfig config;
    config.levels = levels;
    config.angular_step = 0.01;
    CorrelativeMatcher matcher(room, config);
    // A window on the truth, and windows beside it where the best is only a partial fit.
    const std::vector<Eigen::Vector3d> centres{
        {3.27, 2.24, -0.38}, {3.6, 2.0, -0.3}, {5.0, 4.0, 0.3}};
    for (const Eigen::Vector3d& centre : centres) {
      SearchWindow window;
      window.centre = centre;
      window.linear = 0.3;
      window.angular = 0.08;
      const CorrelativeMatch m = matcher.match(sparse, window, 0.0);
      ASSERT_TRUE(m.found);
      const double brute = brute_force_best(matcher, sparse, window);
      EXPECT_NEAR(m.score, brute, 1e-9) << "levels " << levels << " centre " << centre.transpose();
      EXPECT_NEAR(matcher.score(sparse, m.pose), m.score, 1e-9);
      EXPECT_NEAR(m.second_score, std::max(0.0, brute_force_best(matcher, sparse, window, &m.pose)),
                  1e-9);
      // Both passes together scored fewer nodes than two exhaustive searches: the bounds pruned.
      EXPECT_LT(m.candidates_scored, 2u * 13 * 13 * 17);
    }
  }
}

TEST(CorrelativeMatcher, FindsNothingScoringBelowTheMinimum) {
  const Points2 room = asymmetric_room();
  CorrelativeMatcher matcher(room, CorrelativeMatcherConfig{});
  SearchWindow window;
  window.centre = Eigen::Vector3d(5, 3.5, 0);
  window.linear = 1.0;
  window.angular = 0.3;
  const Points2 here = every_other(seen_from(room, Eigen::Vector3d(5.3, 3.2, 0.1), 0.02));
  const Points2 elsewhere = every_other(seen_from(corridor(), Eigen::Vector3d(0.3, 0, 0.1), 0.02));
  EXPECT_TRUE(matcher.match(here, window, 0.6).found);  // the same threshold passes a true match
  const CorrelativeMatch other = matcher.match(elsewhere, window, 0.6);
  EXPECT_FALSE(other.found);
  EXPECT_EQ(other.second_score, 0.0);
  EXPECT_GT(other.candidates_scored, 0u);
  EXPECT_FALSE(matcher.match(here, window, 0.99).found);  // noise keeps the score below 0.99
  EXPECT_FALSE(matcher.match({}, window, 0.0).found);
}

TEST(CorrelativeMatcher, ReportsALookAlikeInACorridorButNotInARoom) {
  CorrelativeMatcherConfig config;
  SearchWindow window;
  window.linear = 1.5;  // the truth at x = 0.6 and its look-alike at x = -1.4 are both inside
  window.angular = 0.1;
  const Points2 hall = corridor();
  const Points2 view = every_other(seen_from(hall, Eigen::Vector3d(0.6, 0.05, 0.02), 0.01, 6.0));
  const CorrelativeMatch ambiguous = CorrelativeMatcher(hall, config).match(view, window, 0.5);
  ASSERT_TRUE(ambiguous.found);
  EXPECT_GT(ambiguous.second_score, 0.95 * ambiguous.score);
  EXPECT_LE(ambiguous.second_score, ambiguous.score);
  // The look-alike is 2 m from the best: an ambiguity radius beyond it leaves it out.
  config.ambiguity_radius = 1.9;
  EXPECT_GT(CorrelativeMatcher(hall, config).match(view, window, 0.5).second_score,
            0.95 * ambiguous.score);
  config.ambiguity_radius = 2.5;
  EXPECT_LT(CorrelativeMatcher(hall, config).match(view, window, 0.5).second_score,
            0.8 * ambiguous.score);
  config.ambiguity_radius = 0.5;

  const Points2 room = asymmetric_room();
  window.centre = Eigen::Vector3d(5, 3.5, 0);
  const Points2 scan = every_other(seen_from(room, Eigen::Vector3d(5.6, 3.55, 0.02), 0.01, 6.0));
  const CorrelativeMatch distinct = CorrelativeMatcher(room, config).match(scan, window, 0.5);
  ASSERT_TRUE(distinct.found);
  EXPECT_LT(distinct.second_score, 0.7 * distinct.score);
}

// A square room looks the same turned by a quarter turn about its centre: those poses are near in
// translation but far in yaw, so they count as look-alikes.
TEST(CorrelativeMatcher, ReportsATurnedLookAlikeInASquareRoom) {
  Points2 square;
  add_box(square, {-3.013, -3.007}, {2.987, 2.993});
  const Points2 scan = every_other(seen_from(square, Eigen::Vector3d(0.1, -0.05, 0.1), 0.01));
  SearchWindow window;
  window.linear = 0.3;
  window.angular = 3.2;  // all yaws
  const CorrelativeMatch m = CorrelativeMatcher(square, {}).match(scan, window, 0.5);
  ASSERT_TRUE(m.found);
  EXPECT_GT(m.second_score, 0.95 * m.score);
}

TEST(CorrelativeMatcher, ReturnsOnlyPosesInsideTheWindow) {
  const Points2 room = asymmetric_room();
  const Eigen::Vector3d truth(4.62, 2.63, 0.21);
  const Points2 scan = every_other(seen_from(room, truth, 0.01));
  CorrelativeMatcher matcher(room, CorrelativeMatcherConfig{});
  SearchWindow window;
  window.centre = Eigen::Vector3d(4, 3, 0);
  window.linear = 1.0;
  window.angular = 0.5;
  const CorrelativeMatch inside = matcher.match(scan, window, 0.0);
  ASSERT_TRUE(inside.found);
  EXPECT_NEAR(inside.pose.x(), truth.x(), 0.08);  // truth inside
  EXPECT_TRUE(matcher.is_peak(scan, inside.pose));

  window.linear = 0.3;    // the truth is 0.62 m away in x and 0.37 m in y
  window.angular = 0.15;  // and 0.21 rad in yaw
  const CorrelativeMatch m = matcher.match(scan, window, 0.0);
  ASSERT_TRUE(m.found);
  EXPECT_LE(std::abs(m.pose.x() - 4), 0.3 + 1e-9);
  EXPECT_LE(std::abs(m.pose.y() - 3), 0.3 + 1e-9);
  EXPECT_LE(std::abs(m.pose.z()), 0.15 + 1e-9);
  EXPECT_LT(m.score, matcher.score(scan, truth));
  EXPECT_FALSE(matcher.is_peak(scan, m.pose));  // on the rim, the score rising to the truth
}

// Two views of a plain corridor, the older one of x = 0..10, the newer of x = -5..5 in the same
// frame (a vehicle that took off facing along it and landed facing back): sliding the newer one
// along the axis overlaps more wall the further it goes, so the window's best lies on its rim,
// 1 m from the truth, and scores well; it is a slope, not a peak.
TEST(CorrelativeMatcher, TheRimOfACorridorsSlopeIsNoPeak) {
  Points2 older;
  add_wall(older, {0.013, -1.007}, {10.013, -1.007});
  add_wall(older, {0.013, 0.993}, {10.013, 0.993});
  Points2 newer;
  add_wall(newer, {-5.013, -1.007}, {5.013, -1.007});
  add_wall(newer, {-5.013, 0.993}, {5.013, 0.993});
  const CorrelativeMatcher matcher(older, {});
  SearchWindow window;
  window.linear = 1.0;
  window.angular = 0.05;
  const CorrelativeMatch m = matcher.match(every_other(newer), window, 0.3);
  ASSERT_TRUE(m.found);
  EXPECT_NEAR(m.pose.x(), 1.0, 0.051);
  EXPECT_FALSE(matcher.is_peak(every_other(newer), m.pose));
}

TEST(CorrelativeMatcher, ScoresZeroOffTheGridAndRejectsABadConfiguration) {
  const Points2 room = asymmetric_room();
  CorrelativeMatcher matcher(room, CorrelativeMatcherConfig{});
  const Points2 scan = every_other(seen_from(room, Eigen::Vector3d(5, 3, 0.1), 0.01));
  EXPECT_GT(matcher.score(scan, Eigen::Vector3d(5, 3, 0.1)), 0.8);
  EXPECT_EQ(matcher.score(scan, Eigen::Vector3d(50, 3, 0.1)), 0.0);
  EXPECT_EQ(matcher.score(scan, Eigen::Vector3d(-1e12, 3, 0.1)), 0.0);
  SearchWindow far;
  far.centre = Eigen::Vector3d(50, 3, 0.1);
  EXPECT_FALSE(matcher.match(scan, far, 1e-6).found);
  EXPECT_FALSE(CorrelativeMatcher({}, CorrelativeMatcherConfig{}).match(scan, far, 1e-6).found);

  CorrelativeMatcherConfig bad;
  bad.resolution = 0.0;
  EXPECT_THROW(CorrelativeMatcher(room, bad), std::invalid_argument);
  bad = CorrelativeMatcherConfig{};
  bad.levels = 0;
  EXPECT_THROW(CorrelativeMatcher(room, bad), std::invalid_argument);
}

}  // namespace
}  // namespace uavslam::backend
