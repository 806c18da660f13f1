#include "core/NearestNeighbourIndex.hpp"

#include <stdexcept>

#include "core/BruteForceIndex.hpp"
#include "core/ExactOctreeIndex.hpp"
#include "core/FlannIndex.hpp"

namespace uavslam {

std::unique_ptr<NearestNeighbourIndex> make_nearest_neighbour_index(
    const SlamConfig::NearestNeighbour& config) {
  if (config.index == "flann") {
    return std::make_unique<FlannIndex>(config.flann_trees, config.flann_checks);
  }
  if (config.index == "exact") return std::make_unique<ExactOctreeIndex>();
  if (config.index == "brute") return std::make_unique<BruteForceIndex>();
  throw std::invalid_argument("unknown nearest-neighbour index '" + config.index +
                              "' (expected flann, exact or brute)");
}

}  // namespace uavslam
