// The world map d: every point the keyframes added, with a nearest-neighbour index over them
// (the seed's `worldmap`, Figure 5.15). It only grows; the index is extended, not rebuilt.
#pragma once

#include <memory>

#include "core/NearestNeighbourIndex.hpp"

namespace uavslam {

class WorldMap {
 public:
  explicit WorldMap(std::unique_ptr<NearestNeighbourIndex> index);

  // worldmap.addPoints(points): step 5 of the seed's algorithm.
  void add_points(const Points& points);

  // The nearest map point d_i of each query point m_i (step 1).
  void find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const;
  // The same after the queries moved a little: `nearest` holds their previous neighbours.
  void find_nearest_again(const Points& queries, std::vector<Neighbour>& nearest) const;

  const Vec3& point(std::size_t i) const { return points_[i]; }
  const Points& points() const { return points_; }
  std::size_t size() const { return points_.size(); }
  bool empty() const { return points_.empty(); }

 private:
  Points points_;
  std::unique_ptr<NearestNeighbourIndex> index_;
};

}  // namespace uavslam
