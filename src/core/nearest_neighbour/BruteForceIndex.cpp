#include "core/nearest_neighbour/BruteForceIndex.hpp"

#include <limits>

namespace uavslam {

void BruteForceIndex::add_points(const Points& points) {
  points_.insert(points_.end(), points.begin(), points.end());
}

void BruteForceIndex::find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const {
  nearest.resize(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) {
    Neighbour best{0, std::numeric_limits<double>::infinity()};
    for (std::size_t j = 0; j < points_.size(); ++j) {
      const double d2 = (points_[j] - queries[i]).squaredNorm();
      if (d2 < best.squared_distance) best = {j, d2};
    }
    nearest[i] = best;
  }
}

}  // namespace uavslam
