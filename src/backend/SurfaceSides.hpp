// Were the surfaces a loop lays on each other seen from the same side? A wall is seen from the
// room it bounds: its points' normals, turned toward the scanner that saw them, point into that
// room. A false loop in a building of corridors lays one corridor's wall onto the other side of
// the block it runs along (a ring corridor's outer wall onto the central block's face, seen from
// inside the block): the points coincide, so the correlative score is high, but the normals face
// each other. A true loop pairs points whose normals agree. Where a corridor's walls hold the
// match across and only its niches or doors hold it along, a loop from the way back (the other
// faces of each niche seen) slides one face onto the other, the niche's width along: most pairs
// (the walls) agree, but those along the axis, the ones that placed the loop there, are opposed.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace uavslam::backend {

// 2D points, each with its unit normal turned toward the scanner that saw it (zero: none known).
struct SurfacePoints {
  std::vector<Eigen::Vector2d> points;
  std::vector<Eigen::Vector2d> normals;  // one per point
};

struct SideCount {
  std::size_t paired = 0;   // scan points with a normal, a reference point with one within reach
  std::size_t opposed = 0;  // of those, the pairs whose normals point away from each other
  // The pairs whose normal lies within 45 degrees of the direction the pairs fix least (a
  // corridor's axis: the niches' and doors' faces), and of those the opposed.
  std::size_t weak_paired = 0;
  std::size_t weak_opposed = 0;
  double opposed_share() const { return share(opposed, paired); }
  double weak_opposed_share() const { return share(weak_opposed, weak_paired); }

 private:
  static double share(std::size_t part, std::size_t whole) {
    return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
  }
};

// `scan` moved by `pose` (x, y, yaw) into `reference`'s frame, each of its points (with a normal)
// paired with the nearest reference point within `reach` whose normal faces the same way (a
// non-negative dot product), else with the nearest facing the other way: then opposed.
SideCount compare_sides(const SurfacePoints& reference, const SurfacePoints& scan,
                        const Eigen::Vector3d& pose, double reach);

// The unit normal of a point at `point` (sensor frame, the scanner at the origin) turned toward
// the scanner; zero for none (a zero or mostly vertical normal: a floor's, a ceiling's).
Eigen::Vector2d toward_scanner(const Eigen::Vector2d& point, const Eigen::Vector3d& normal);

}  // namespace uavslam::backend
