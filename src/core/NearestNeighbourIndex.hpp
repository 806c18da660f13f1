// The nearest-neighbour search over the world map (step 1 of the seed's ICP), behind one interface
// so the real-time FLANN search, the exact octree search of the offline mode and a brute-force
// reference are interchangeable.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/SlamConfig.hpp"
#include "core/Types.hpp"

namespace uavslam {

struct Neighbour {
  std::size_t index = 0;          // into the points in the order they were added
  double squared_distance = 0.0;  // m^2
  // Set by an index that can answer find_nearest_again without a search (the octree): where the
  // query was when it last searched, the second-nearest point and its distance then (m), and
  // the map's size then.
  Vec3 searched_from = Vec3::Zero();
  std::size_t second_index = 0;
  double second_distance = 0.0;
  std::size_t searched_size = 0;
};

class NearestNeighbourIndex {
 public:
  virtual ~NearestNeighbourIndex() = default;

  // Appends points; indices of earlier points stay valid (the map only grows).
  virtual void add_points(const Points& points) = 0;
  virtual std::size_t size() const = 0;
  // For each query the nearest indexed point; `nearest` is resized to queries.size().
  virtual void find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const = 0;
  // The same, for queries that moved a little since `nearest` was found for them (the next ICP
  // iteration, or the next scan's points): an exact index starts from the old neighbours as its
  // bounds. `nearest` may hold fewer or more entries than there are queries.
  virtual void find_nearest_again(const Points& queries, std::vector<Neighbour>& nearest) const {
    find_nearest(queries, nearest);
  }
};

// The index config.index names: approximate kd-trees, an exact octree, or every point (reference).
std::unique_ptr<NearestNeighbourIndex> make_nearest_neighbour_index(
    const SlamConfig::NearestNeighbour& config);

}  // namespace uavslam
