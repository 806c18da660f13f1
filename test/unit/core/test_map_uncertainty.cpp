// The map's own uncertainty: a match inherits the covariance of the keyframes whose points it
// paired with, each in the directions its pairs fixed.
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/extensions/MapUncertainty.hpp"

namespace uavslam {
namespace {

// Position covariances with a heading known exactly.
Eigen::Matrix4d isotropic(double variance) {
  Eigen::Matrix4d covariance = variance * Eigen::Matrix4d::Identity();
  covariance(3, 3) = 0.0;
  return covariance;
}

Eigen::Matrix4d diagonal(double x, double y, double z) {
  return Eigen::Vector4d(x, y, z, 0.0).asDiagonal();
}

// Pairs on walls (horizontal normal n, level beams) or the floor (vertical), each with the map
// point it paired with.
struct Pairs {
  Correspondences pairs;
  Pairs& wall(std::size_t map_index, const Vec3& normal, const Vec3& at = Vec3::Zero()) {
    add(map_index, normal, Vec3(1.0, 1.0, 0.0), at);
    return *this;
  }
  Pairs& floor(std::size_t map_index) {
    add(map_index, Vec3::Zero(), Vec3(0.0, 0.0, 1.0), Vec3::Zero());
    return *this;
  }
  void add(std::size_t map_index, const Vec3& normal, const Vec3& weights, const Vec3& at) {
    pairs.scan.push_back(at);
    pairs.map.push_back(at);
    pairs.map_index.push_back(map_index);
    pairs.weights.push_back(weights);
    pairs.scan_normals.push_back(normal);
  }
};

// The covariance a match inherits, from keyframes whose heading's drift is not modelled.
Eigen::Matrix4d covariance_of(const MapUncertainty& map, const Correspondences& pairs) {
  return map.of_match(pairs, Vec3::Zero()).covariance();
}

MapUncertainty three_keyframes() {
  MapUncertainty map;
  map.add_keyframe(0, Vec3::Zero(),
                   isotropic(0.0));  // points 0..99: the take-off, the map's anchor
  map.add_keyframe(100, Vec3::Zero(), isotropic(4.0));  // points 100..149
  map.add_keyframe(150, Vec3::Zero(), isotropic(1.0));  // points 150..
  return map;
}

TEST(MapUncertainty, AMatchOnOneKeyframeInheritsItsCovariance) {
  const MapUncertainty map = three_keyframes();
  EXPECT_TRUE(covariance_of(map, Pairs{}.pairs).isZero());
  EXPECT_TRUE(
      covariance_of(map, Pairs{}.wall(0, Vec3::UnitX()).wall(5, Vec3::UnitY()).floor(99).pairs)
          .isZero());
  EXPECT_TRUE(
      covariance_of(map, Pairs{}.wall(100, Vec3::UnitX()).wall(149, Vec3::UnitY()).floor(120).pairs)
          .isApprox(isotropic(4.0)));
  EXPECT_TRUE(covariance_of(
                  map, Pairs{}.wall(150, Vec3::UnitX()).wall(1000, Vec3::UnitY()).floor(999).pairs)
                  .isApprox(isotropic(1.0)));
}

// A corridor: the anchor's many wall pairs fix y, one door edge from a drifted keyframe fixes x.
// The door edge's keyframe alone says how well x is known, however many pairs the anchor holds.
TEST(MapUncertainty, EachKeyframeCountsInTheDirectionsItsPairsFixed) {
  const MapUncertainty map = three_keyframes();
  Pairs corridor;
  for (std::size_t i = 0; i < 50; ++i) corridor.wall(i, Vec3::UnitY()).floor(i);
  corridor.wall(120, Vec3::UnitX());
  const Eigen::Matrix4d covariance = covariance_of(map, corridor.pairs);
  EXPECT_NEAR(covariance(0, 0), 4.0, 1e-9);
  EXPECT_NEAR(covariance(1, 1), 0.0, 1e-9);
  EXPECT_NEAR(covariance(2, 2), 0.0, 1e-9);
}

// Keyframes share their error as far as they share its sources. Two independent ones that fix the
// same direction equally average their noises: (4 + 1) / 4. A keyframe that matched on another
// carries that one's error whole, plus its own: a match on both, e_1 + n_2 / 2, has 4 + 1 / 4.
TEST(MapUncertainty, KeyframesShareTheErrorsTheyCameFrom) {
  const MapUncertainty independent = three_keyframes();
  const Correspondences both = Pairs{}.wall(101, Vec3::UnitX()).wall(151, Vec3::UnitX()).pairs;
  EXPECT_NEAR(covariance_of(independent, both)(0, 0), 1.25, 1e-9);
  EXPECT_NEAR(covariance_of(independent, both)(1, 1), 0.0, 1e-9);

  MapUncertainty chain;
  chain.add_keyframe(0, Vec3::Zero(), isotropic(0.0));
  chain.add_keyframe(100, Vec3::Zero(), isotropic(4.0));
  const MapError matched = chain.of_match(Pairs{}.wall(120, Vec3::UnitX()).pairs, Vec3::Zero());
  chain.add_keyframe(150, Vec3::Zero(), isotropic(1.0), Eigen::Vector4d::Zero(),
                     Eigen::Vector4d::Zero(), matched.error);
  EXPECT_NEAR(covariance_of(chain, Pairs{}.wall(151, Vec3::UnitX()).pairs)(0, 0), 5.0, 1e-9);
  EXPECT_NEAR(covariance_of(chain, both)(0, 0), 4.25, 1e-9);
}

// Each keyframe's weight in the heading the map holds where the pairs are: its share of their
// horizontal information (floor pairs hold none).
TEST(MapUncertainty, AKeyframesHeadingShareIsItsShareOfTheWallPairs) {
  const MapUncertainty map = three_keyframes();
  const auto shares = map.heading_shares(Pairs{}
                                             .wall(1, Vec3::UnitX())
                                             .wall(2, Vec3::UnitY())
                                             .wall(3, Vec3::UnitX())
                                             .wall(120, Vec3::UnitY())
                                             .floor(160)
                                             .pairs);
  ASSERT_EQ(shares.size(), 2u);
  EXPECT_EQ(shares[0].first, 0u);
  EXPECT_NEAR(shares[0].second, 0.75, 1e-12);
  EXPECT_EQ(shares[1].first, 1u);
  EXPECT_NEAR(shares[1].second, 0.25, 1e-12);
}

// Two walls along x (normals y) and two faces across (normals x) around (10, 0).
Correspondences walls_around_ten_metres_east() {
  return Pairs{}
      .wall(1, Vec3::UnitY(), Vec3(10.0, 1.0, 0.0))
      .wall(2, Vec3::UnitY(), Vec3(10.0, -1.0, 0.0))
      .wall(3, Vec3::UnitX(), Vec3(11.0, 0.0, 0.0))
      .wall(4, Vec3::UnitX(), Vec3(9.0, 0.0, 0.0))
      .pairs;
}

// A keyframe taken at the origin with its position exact and its heading known to 0.1 rad; the
// vehicle matches its points 10 m east, between two walls along x (normals y) and two faces
// across (normals x). A turn of the keyframe by eps moves the walls' points north by 10 eps: the
// match inherits sigma_y = 10 x 0.1 = 1 m, none along x (the faces turn along their own plane),
// the keyframe's heading, and the two errors' full correlation (10 x 0.01).
TEST(MapUncertainty, AKeyframesHeadingErrorReachesAFarMatchByItsLeverArm) {
  Eigen::Matrix4d heading_only = Eigen::Matrix4d::Zero();
  heading_only(3, 3) = 0.01;
  MapUncertainty map;
  map.add_keyframe(0, Vec3::Zero(), heading_only);
  const Eigen::Matrix4d far = covariance_of(map, walls_around_ten_metres_east());
  EXPECT_NEAR(far(0, 0), 0.0, 1e-12);
  EXPECT_NEAR(far(1, 1), 1.0, 1e-9);
  EXPECT_NEAR(far(3, 3), 0.01, 1e-12);
  EXPECT_NEAR(far(1, 3), 0.1, 1e-12);
  // The same points matched from a keyframe taken beside them: no lever arm, no inherited error.
  MapUncertainty near;
  near.add_keyframe(0, Vec3(10.0, 0.0, 0.0), heading_only);
  const Eigen::Matrix4d beside = covariance_of(near, walls_around_ten_metres_east());
  EXPECT_NEAR((beside.topLeftCorner<3, 3>().norm()), 0.0, 1e-12);
}

// Walls along x 10 and 12 m east (normals y) and two faces across (normals x): a scan of them
// fixes x, y and its heading.
Correspondences walls_ten_to_twelve_metres_east() {
  return Pairs{}
      .wall(1, Vec3::UnitY(), Vec3(10.0, 1.0, 0.0))
      .wall(2, Vec3::UnitY(), Vec3(10.0, -1.0, 0.0))
      .wall(3, Vec3::UnitY(), Vec3(12.0, 1.0, 0.0))
      .wall(4, Vec3::UnitY(), Vec3(12.0, -1.0, 0.0))
      .wall(5, Vec3::UnitX(), Vec3(13.0, 0.0, 0.0))
      .wall(6, Vec3::UnitX(), Vec3(9.0, 0.0, 0.0))
      .pairs;
}

// A match that turns the scan as well (icp.heading: every_scan) follows a keyframe's turn about
// that keyframe's position: matched where the keyframe was taken, the far walls' turn is the
// scan's own heading, not a shift of 10 m x eps; matched 10 m east of the keyframe, it is that
// lever arm's shift. Matched without turning the scan, the walls' lever arm counts either way.
TEST(MapUncertainty, AMatchThatTurnsFollowsAKeyframesTurnByTheLeverArmToTheVehicle) {
  Eigen::Matrix4d heading_only = Eigen::Matrix4d::Zero();
  heading_only(3, 3) = 0.01;
  MapUncertainty map;
  map.add_keyframe(0, Vec3::Zero(), heading_only);
  const Correspondences pairs = walls_ten_to_twelve_metres_east();
  const Eigen::Matrix4d at_keyframe =
      map.of_match(pairs, Vec3::Zero(), Eigen::Vector2d::Zero(), true).covariance();
  EXPECT_NEAR((at_keyframe.topLeftCorner<3, 3>().norm()), 0.0, 1e-9);
  EXPECT_NEAR(at_keyframe(3, 3), 0.01, 1e-9);
  const Eigen::Matrix4d east =
      map.of_match(pairs, Vec3(10.0, 0.0, 0.0), Eigen::Vector2d::Zero(), true).covariance();
  EXPECT_NEAR(east(0, 0), 0.0, 1e-9);
  EXPECT_NEAR(east(1, 1), 1.0, 1e-9);
  EXPECT_NEAR(east(1, 3), 0.1, 1e-9);
  EXPECT_NEAR(east(3, 3), 0.01, 1e-9);
  const Eigen::Matrix4d unturned = map.of_match(pairs, Vec3::Zero()).covariance();
  EXPECT_GT(unturned(1, 1), 1.0);
}

// Two keyframes a motion prior carried down a corridor, off along its axis by a metre: pairs on
// the walls behind (keyframe 1) and ahead (keyframe 2), some of their normals tilted a little, as
// noisy normals are. Sharing the prior's error (CorrelatedError::carried), the two are
// shifted together and a turning match between them is shifted with them, its heading and its
// distance to the walls untouched; taken as independent noises, their difference reads as a
// turn.
TEST(MapUncertainty, KeyframesCarriedThroughOneBlindStretchShiftTogether) {
  const Eigen::Matrix4d along_axis = diagonal(1.0, 0.0, 0.0);
  Pairs walls;
  for (int i = 0; i < 5; ++i) {
    const double behind = -1.0 - i;
    const double ahead = 3.0 + i;
    const double tilt = 0.02 * (i - 2);  // the normals' noise, along the wall
    walls.wall(100 + i, Vec3(tilt, 1.0, 0.0).normalized(), Vec3(behind, 1.0, 0.0))
        .wall(110 + i, Vec3(0.0, -1.0, 0.0), Vec3(behind, -1.0, 0.0))
        .wall(200 + i, Vec3(0.0, 1.0, 0.0), Vec3(ahead, 1.0, 0.0))
        .wall(210 + i, Vec3(-tilt, -1.0, 0.0).normalized(), Vec3(ahead, -1.0, 0.0));
  }
  const Vec3 between(1.0, 0.0, 0.0);
  CorrelatedError carried;
  carried.add_noise(CorrelatedError::carried(0), along_axis);
  MapUncertainty shared;
  shared.add_keyframe(0, Vec3::Zero(), isotropic(0.0));
  shared.add_keyframe(100, Vec3::Zero(), isotropic(0.0), {}, {}, carried);
  shared.add_keyframe(200, Vec3(2.0, 0.0, 0.0), isotropic(0.0), {}, {}, carried);
  const Eigen::Matrix4d together =
      shared.of_match(walls.pairs, between, Eigen::Vector2d::Zero(), true).covariance();
  EXPECT_NEAR(together(0, 0), 1.0, 1e-9);
  EXPECT_NEAR(together(1, 1), 0.0, 1e-12);
  EXPECT_NEAR(together(3, 3), 0.0, 1e-12);
  MapUncertainty independent;
  independent.add_keyframe(0, Vec3::Zero(), isotropic(0.0));
  independent.add_keyframe(100, Vec3::Zero(), along_axis);
  independent.add_keyframe(200, Vec3(2.0, 0.0, 0.0), along_axis);
  const Eigen::Matrix4d apart =
      independent.of_match(walls.pairs, between, Eigen::Vector2d::Zero(), true).covariance();
  EXPECT_GT(apart(3, 3), 1e-7);  // about 0.8 mrad from a metre of independent shifts
}

// The heading's drift: a keyframe made 10 s after the first is off by r x 10 s, a = (0, 0, 0, 10)
// per rad/s. Matched from where it was taken, against points 10 m east: an unturned scan is pulled
// north by the lever arm (g = (0, 10) per rad: 100 per rad/s); a scan turned as its map is, as
// the source turns it too, matches where it stands (the scan's own drift terms, the same 10 s).
TEST(MapUncertainty, AScanTurnedAsItsMapIsMatchesWhereAWorldTurnedAsAWholePutsIt) {
  MapUncertainty map;
  map.add_keyframe(0, Vec3::Zero(), isotropic(0.0), Eigen::Vector4d(0.0, 0.0, 0.0, 10.0));
  const Correspondences pairs = walls_around_ten_metres_east();
  const MapError unturned = map.of_match(pairs, Vec3::Zero());
  EXPECT_TRUE(unturned.drift.isApprox(Eigen::Vector4d(0.0, 100.0, 0.0, 10.0)));
  EXPECT_TRUE(unturned.covariance().isZero());
  const MapError turned = map.of_match(pairs, Vec3::Zero(), Eigen::Vector2d(10.0, 0.0));
  EXPECT_NEAR(turned.drift.head<3>().norm(), 0.0, 1e-9);
  // Matched 10 m east, among the points: the world turned about the first keyframe moves the
  // match by 10 m x the turn, north, whether the scan is turned or not (no lever about itself).
  const MapError far = map.of_match(pairs, Vec3(10.0, 0.0, 0.0), Eigen::Vector2d(10.0, 0.0));
  EXPECT_TRUE(far.drift.isApprox(Eigen::Vector4d(0.0, 100.0, 0.0, 10.0)));
  // The total: at r = 1 mrad/s known to 1 mrad/s, sigma_y^2 = (100 r)^2 + 100^2 var(r).
  EXPECT_NEAR(far.total(0.001, 1e-6)(1, 1), 0.01 + 0.01, 1e-12);
  EXPECT_NEAR(far.total(0.001, 1e-6)(0, 0), 0.0, 1e-12);
}

// What was applied of the drift is no error: a keyframe whose heading was corrected by the drift
// the rate says (h = a r) carries none of the known part, only the rate's uncertainty; turned
// later by the back end (MapUncertainty::turn), likewise, its position placed again.
TEST(MapUncertainty, TheDriftAppliedIsNoError) {
  const double r = 0.001;
  MapUncertainty corrected;
  corrected.add_keyframe(0, Vec3::Zero(), isotropic(0.0), Eigen::Vector4d(0.0, 0.0, 0.0, 10.0),
                         Eigen::Vector4d(0.0, 0.0, 0.0, 10.0 * r));
  const Correspondences pairs = walls_around_ten_metres_east();
  EXPECT_NEAR(corrected.of_match(pairs, Vec3::Zero()).total(r, 0.0).norm(), 0.0, 1e-12);
  EXPECT_NEAR(corrected.of_match(pairs, Vec3::Zero()).total(r, 1e-6)(1, 1), 0.01, 1e-12);
  MapUncertainty turned;
  turned.add_keyframe(0, Vec3::Zero(), isotropic(0.0), Eigen::Vector4d(0.0, 30.0, 0.0, 10.0));
  EXPECT_NEAR(turned.of_match(pairs, Vec3::Zero()).total(r, 0.0)(1, 1), 0.13 * 0.13, 1e-12);
  turned.turn(0, 10.0 * r, r);
  EXPECT_NEAR(turned.of_match(pairs, Vec3::Zero()).total(r, 0.0).norm(), 0.0, 1e-12);
}

// Moved keyframes turn about their new positions.
TEST(MapUncertainty, MovedKeyframesTurnAboutTheirNewPositions) {
  MapUncertainty map;
  Eigen::Matrix4d heading_only = Eigen::Matrix4d::Zero();
  heading_only(3, 3) = 0.01;
  map.add_keyframe(0, Vec3::Zero(), heading_only);
  EXPECT_THROW(map.move_keyframes({0, 5}, {Vec3::Zero(), Vec3::Zero()}), std::invalid_argument);
  map.move_keyframes({0}, {Vec3(0.0, 5.0, 0.0)});
  const Eigen::Matrix4d moved =
      covariance_of(map, Pairs{}.wall(1, Vec3::UnitX(), Vec3(0.0, 0.0, 0.0)).pairs);
  EXPECT_NEAR(moved(0, 0), 25.0 * 0.01, 1e-9);  // 5 m south of the keyframe, along x
}

TEST(MapUncertainty, AKeyframeThatAddedNothingOwnsNoPoint) {
  MapUncertainty map;
  map.add_keyframe(0, Vec3::Zero(), isotropic(1.0));
  map.add_keyframe(10, Vec3::Zero(),
                   isotropic(9.0));  // every point within the spacing of older ones
  map.add_keyframe(10, Vec3::Zero(), diagonal(2.0, 3.0, 5.0));
  EXPECT_TRUE(
      covariance_of(map, Pairs{}.wall(10, Vec3::UnitX()).wall(11, Vec3::UnitY()).floor(12).pairs)
          .isApprox(diagonal(2.0, 3.0, 5.0)));
  EXPECT_TRUE(
      covariance_of(map, Pairs{}.wall(9, Vec3::UnitX()).wall(9, Vec3::UnitY()).floor(9).pairs)
          .isApprox(isotropic(1.0)));
}

TEST(MapUncertainty, PairsBeforeTheFirstKeyframeOrWithoutInformationCountForNothing) {
  MapUncertainty map;
  map.add_keyframe(10, Vec3::Zero(), isotropic(4.0));
  EXPECT_TRUE(covariance_of(map, Pairs{}.wall(3, Vec3::UnitX()).pairs).isZero());
  EXPECT_TRUE(covariance_of(map, Pairs{}.wall(12, Vec3::Zero()).pairs).isZero());  // no normal
}

}  // namespace
}  // namespace uavslam
