// Approximate nearest neighbours by FLANN's randomised kd-trees: the seed's real-time search
// (ch. 5.4.3.1, modification 1). The only translation unit that instantiates FLANN (it is slow
// to compile). FLANN 1.9.2 shuffles the points with std::random_device when it builds its trees,
// so runs on this index do not repeat bit for bit; the octree's do.
#pragma once

#include <memory>

#include "core/NearestNeighbourIndex.hpp"

namespace uavslam {

class FlannIndex final : public NearestNeighbourIndex {
 public:
  // trees: randomised kd-trees; checks: leaves visited per query (more = exact-er and slower).
  FlannIndex(int trees, int checks);
  ~FlannIndex() override;

  void add_points(const Points& points) override;
  std::size_t size() const override;
  void find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace uavslam
