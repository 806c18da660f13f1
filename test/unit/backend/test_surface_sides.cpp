#include <cmath>

#include <gtest/gtest.h>

#include "backend/SurfaceSides.hpp"

namespace uavslam::backend {
namespace {

// A straight surface from `from` to `to`, points 5 cm apart, as a scanner at `scanner` sees it:
// its normal turned toward the scanner (its sensor frame is the world here).
void add_surface(SurfacePoints& surface, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                 const Eigen::Vector2d& scanner) {
  const Eigen::Vector2d along = (to - from).normalized();
  const Eigen::Vector3d normal(-along.y(), along.x(), 0.0);
  const int steps = static_cast<int>(std::round((to - from).norm() / 0.05));
  for (int k = 0; k <= steps; ++k) {
    const Eigen::Vector2d p = from + 0.05 * k * along;
    surface.points.push_back(p);
    surface.normals.push_back(toward_scanner(p - scanner, normal));
  }
}

// A wall along x at y = wall_y, x from 0 to 4.
void add_wall(SurfacePoints& surface, double wall_y, const Eigen::Vector2d& scanner) {
  add_surface(surface, {0.0, wall_y}, {4.0, wall_y}, scanner);
}

TEST(SurfaceSides, TheNormalIsTurnedTowardTheScanner) {
  EXPECT_TRUE(toward_scanner({2.0, 1.0}, {0.0, 1.0, 0.0}).isApprox(Eigen::Vector2d(0.0, -1.0)));
  EXPECT_TRUE(toward_scanner({2.0, -1.0}, {0.0, 1.0, 0.0}).isApprox(Eigen::Vector2d(0.0, 1.0)));
  EXPECT_TRUE(toward_scanner({2.0, 1.0}, {0.0, 0.0, 0.0}).isZero());  // none known
  EXPECT_TRUE(toward_scanner({2.0, 1.0}, {0.1, 0.1, 1.0}).isZero());  // a floor's
}

TEST(SurfaceSides, AWallSeenFromTheSameSideAgrees) {
  SurfacePoints reference, scan;
  add_wall(reference, 1.0, {2.0, 0.0});
  add_wall(scan, 1.0, {1.0, -1.5});  // the same wall, from elsewhere on the same side
  const SideCount count = compare_sides(reference, scan, Eigen::Vector3d::Zero(), 0.1);
  EXPECT_EQ(count.paired, scan.points.size());
  EXPECT_EQ(count.opposed, 0u);
}

// A corridor's wall laid on the far face of the block it runs along: the same points, the other
// side.
TEST(SurfaceSides, AWallLaidOnTheFarFaceOfABlockIsOpposed) {
  SurfacePoints reference, scan;
  add_wall(reference, 1.0, {2.0, 0.0});  // the block's south face, seen from the corridor below
  add_wall(scan, 0.0, {2.0, 1.75});      // the corridor's outer wall, seen from above it
  const Eigen::Vector3d onto_the_block(0.0, 1.0, 0.0);  // the look-alike: one wall onto the other
  const SideCount count = compare_sides(reference, scan, onto_the_block, 0.1);
  EXPECT_EQ(count.paired, scan.points.size());
  EXPECT_DOUBLE_EQ(count.opposed_share(), 1.0);
}

// A face across the corridor at x = face_x, y from 1 to 2 (a niche's side).
void add_face(SurfacePoints& surface, double face_x, const Eigen::Vector2d& scanner) {
  add_surface(surface, {face_x, 1.0}, {face_x, 2.0}, scanner);
}

// Along a corridor only a niche's faces hold the match; out east the scanner sees the niche's far
// face (at x = 3, from the west), back west its other face (at x = 2, from the east). Laid on each
// other, 1 m along, the walls agree and the faces that placed the loop are opposed.
TEST(SurfaceSides, ANichesFaceLaidOnItsOtherFaceIsOpposedAlongTheCorridor) {
  SurfacePoints out, back;
  add_wall(out, 1.0, {0.0, 0.0});
  add_wall(out, -1.0, {0.0, 0.0});
  add_face(out, 3.0, {0.0, 0.0});
  add_wall(back, 1.0, {4.0, 0.0});
  add_wall(back, -1.0, {4.0, 0.0});
  add_face(back, 2.0, {4.0, 0.0});
  const SideCount slid = compare_sides(out, back, Eigen::Vector3d(1.0, 0.0, 0.0), 0.1);
  EXPECT_LT(slid.opposed_share(), 0.5);  // the walls outnumber the faces
  // The face's 21 points (the axis is the weakest direction), but for the corners where face
  // and wall meet.
  EXPECT_GE(slid.weak_paired, 18u);
  EXPECT_LE(slid.weak_paired, 21u);
  EXPECT_GT(slid.weak_opposed_share(), 0.9);
  const SideCount in_place = compare_sides(out, back, Eigen::Vector3d::Zero(), 0.1);
  EXPECT_EQ(in_place.opposed, 0u);  // the two faces 1 m apart: unpaired
  EXPECT_DOUBLE_EQ(in_place.weak_opposed_share(), 0.0);
}

// A partition 5 cm thick, seen from both sides in the reference: a scan of one side finds that
// side, not the other within reach.
TEST(SurfaceSides, AThinWallSeenFromBothSidesAgreesWithEither) {
  SurfacePoints reference, north, south;
  add_wall(reference, 1.0, {2.0, -1.0});
  add_wall(reference, 1.05, {2.0, 3.0});
  add_wall(north, 1.05, {1.0, 2.5});
  add_wall(south, 1.0, {1.0, -0.5});
  EXPECT_EQ(compare_sides(reference, north, Eigen::Vector3d::Zero(), 0.1).opposed, 0u);
  EXPECT_EQ(compare_sides(reference, south, Eigen::Vector3d::Zero(), 0.1).opposed, 0u);
  // Seen from one side only, the other side laid on it is opposed.
  SurfacePoints one_side;
  add_wall(one_side, 1.0, {2.0, -1.0});
  EXPECT_DOUBLE_EQ(compare_sides(one_side, north, Eigen::Vector3d::Zero(), 0.1).opposed_share(),
                   1.0);
}

TEST(SurfaceSides, PointsWithoutANormalOrAPartnerAreNotCounted) {
  SurfacePoints reference, scan;
  add_wall(reference, 1.0, {2.0, 0.0});
  scan.points = {{2.0, 1.0}, {2.0, 5.0}, {3.0, 1.0}};
  scan.normals = {Eigen::Vector2d(0.0, -1.0), Eigen::Vector2d(0.0, -1.0), Eigen::Vector2d::Zero()};
  const SideCount count = compare_sides(reference, scan, Eigen::Vector3d::Zero(), 0.1);
  EXPECT_EQ(count.paired, 1u);  // the far point has no partner, the last no normal
  EXPECT_EQ(count.opposed, 0u);
  EXPECT_DOUBLE_EQ(SideCount{}.opposed_share(), 0.0);
}

TEST(SurfaceSides, TheScanIsTurnedAndMovedByThePose) {
  SurfacePoints reference, scan;
  add_wall(reference, 1.0, {2.0, 0.0});
  // The reference wall in a frame turned by 90 degrees about the origin: x = -1, y from 0 to 4,
  // seen from (0, 2).
  for (const Eigen::Vector2d& p : reference.points) scan.points.emplace_back(-p.y(), p.x());
  for (const Eigen::Vector2d& n : reference.normals) scan.normals.emplace_back(-n.y(), n.x());
  const SideCount back = compare_sides(reference, scan, Eigen::Vector3d(0.0, 0.0, -M_PI / 2), 0.1);
  EXPECT_EQ(back.paired, scan.points.size());
  EXPECT_EQ(back.opposed, 0u);
  const SideCount unturned = compare_sides(reference, scan, Eigen::Vector3d::Zero(), 0.1);
  EXPECT_LT(unturned.paired, 5u);
}

}  // namespace
}  // namespace uavslam::backend
