// Exact nearest neighbours by comparing every point: the trivially correct reference that tests
// and benchmarks hold the other indexes against.
#pragma once

#include "core/NearestNeighbourIndex.hpp"

namespace uavslam {

class BruteForceIndex final : public NearestNeighbourIndex {
 public:
  void add_points(const Points& points) override;
  std::size_t size() const override { return points_.size(); }
  void find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const override;

 private:
  Points points_;
};

}  // namespace uavslam
