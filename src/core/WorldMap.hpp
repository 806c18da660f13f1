// The world map d: every point the keyframes added, with a nearest-neighbour index over them
// (the seed's `worldmap`, Figure 5.15). It only grows; the index is extended, not rebuilt.
// Beyond the seed, optionally: a surface normal per point (for the point-to-line metric), and a
// minimum spacing: a keyframe point that lands near a map point is not added, so a wall is held
// once, by the keyframe that saw it first, and a vehicle back in a known place matches that
// original instead of a copy drifted with it.
#pragma once

#include <memory>

#include "core/NearestNeighbourIndex.hpp"

namespace uavslam {

class WorldMap {
 public:
  // min_spacing <= 0: every added point is kept (the seed).
  explicit WorldMap(std::unique_ptr<NearestNeighbourIndex> index, double min_spacing = 0.0);

  // worldmap.addPoints(points): step 5 of the seed's algorithm. `normals` is empty or holds one
  // normal per point (zero = none known). Returns the points kept (all, without a spacing).
  Points add_points(const Points& points, const std::vector<Vec3>& normals = {});

  // The nearest map point d_i of each query point m_i (step 1).
  void find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const;
  // The same after the queries moved a little: `nearest` holds their previous neighbours.
  void find_nearest_again(const Points& queries, std::vector<Neighbour>& nearest) const;

  const Vec3& point(std::size_t i) const { return points_[i]; }
  const Points& points() const { return points_; }
  // Empty unless points were added with normals; then one per point.
  const std::vector<Vec3>& normals() const { return normals_; }
  std::size_t size() const { return points_.size(); }
  bool empty() const { return points_.empty(); }

 private:
  Points points_;
  std::vector<Vec3> normals_;
  std::unique_ptr<NearestNeighbourIndex> index_;
  double min_spacing_;
};

}  // namespace uavslam
