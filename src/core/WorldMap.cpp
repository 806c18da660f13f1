#include "core/WorldMap.hpp"

namespace uavslam {

WorldMap::WorldMap(std::unique_ptr<NearestNeighbourIndex> index, double min_spacing)
    : index_(std::move(index)), min_spacing_(min_spacing) {}

Points WorldMap::add_points(const Points& points, const std::vector<Vec3>& normals) {
  std::vector<Neighbour> nearest;
  const bool filter = min_spacing_ > 0.0 && !points_.empty();
  if (filter) index_->find_nearest(points, nearest);
  Points added;
  added.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (filter && nearest[i].squared_distance < min_spacing_ * min_spacing_) continue;
    added.push_back(points[i]);
    if (!normals.empty()) normals_.push_back(normals[i]);
  }
  points_.insert(points_.end(), added.begin(), added.end());
  if (!added.empty()) index_->add_points(added);
  return added;
}

void WorldMap::find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const {
  index_->find_nearest(queries, nearest);
}

void WorldMap::find_nearest_again(const Points& queries, std::vector<Neighbour>& nearest) const {
  index_->find_nearest_again(queries, nearest);
}

}  // namespace uavslam
