#include "core/NearestNeighbourIndex.hpp"

#include "core/nearest_neighbour/BruteForceIndex.hpp"
#include "core/nearest_neighbour/ExactOctreeIndex.hpp"
#include "core/nearest_neighbour/FlannIndex.hpp"

namespace uavslam {

std::unique_ptr<NearestNeighbourIndex> make_nearest_neighbour_index(
    const SlamConfig::NearestNeighbour& config) {
  switch (config.index) {
    case IndexKind::Flann:
      return std::make_unique<FlannIndex>(config.flann_trees, config.flann_checks);
    case IndexKind::Exact:
      return std::make_unique<ExactOctreeIndex>();
    case IndexKind::Brute:
      break;
  }
  return std::make_unique<BruteForceIndex>();
}

}  // namespace uavslam
