// Exact nearest neighbours through a point octree: the search of the seed's offline variant
// ("uses octree optimisation instead of FLANN for increased accuracy", ch. 5.4.3.3) and the
// accuracy reference for the approximate search.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/NearestNeighbourIndex.hpp"

namespace uavslam {

class ExactOctreeIndex final : public NearestNeighbourIndex {
 public:
  // leaf_capacity: points a leaf holds before it splits into eight octants.
  explicit ExactOctreeIndex(std::size_t leaf_capacity = 32);

  void add_points(const Points& points) override;
  std::size_t size() const override { return points_.size(); }
  void find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const override;
  void find_nearest_again(const Points& queries, std::vector<Neighbour>& nearest) const override;

 private:
  static constexpr std::int32_t kNoChild = -1;
  struct Node {
    Vec3 center;
    double half_size;
    std::array<std::int32_t, 8> children;  // kNoChild where empty; all kNoChild in a leaf
    std::vector<std::uint32_t> points;     // a leaf's points
    bool leaf = true;
  };

  void grow_root_to_contain(const Vec3& p);
  void insert(std::uint32_t point_index);
  void split(std::int32_t node_index);
  int octant_of(const Node& node, const Vec3& p) const;
  std::int32_t make_child(std::int32_t node_index, int octant);
  struct TwoNearest {
    std::uint32_t index = 0;
    double first = 0.0;  // squared distances
    std::uint32_t second_index = 0;
    double second = 0.0;
  };
  void search(std::int32_t node_index, const Vec3& q, TwoNearest& best) const;
  Neighbour searched(const Vec3& q, TwoNearest best) const;
  Neighbour searched_afresh(const Vec3& q) const;  // no earlier answer to start from
  Neighbour again(const Vec3& query, bool warm, const Neighbour& last) const;
  // Queries a thread claims at a time (ParallelLoop): a few microseconds' work.
  static constexpr std::size_t kChunk = 16;

  std::size_t leaf_capacity_;
  Points points_;
  std::vector<Node> nodes_;
  std::int32_t root_ = kNoChild;
};

}  // namespace uavslam
