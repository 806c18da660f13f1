#include "core/WorldMap.hpp"

namespace uavslam {

WorldMap::WorldMap(std::unique_ptr<NearestNeighbourIndex> index) : index_(std::move(index)) {}

void WorldMap::add_points(const Points& points) {
  points_.insert(points_.end(), points.begin(), points.end());
  index_->add_points(points);
}

void WorldMap::find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const {
  index_->find_nearest(queries, nearest);
}

void WorldMap::find_nearest_again(const Points& queries, std::vector<Neighbour>& nearest) const {
  index_->find_nearest_again(queries, nearest);
}

}  // namespace uavslam
