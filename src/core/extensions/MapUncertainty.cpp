#include "core/extensions/MapUncertainty.hpp"

#include <algorithm>

namespace uavslam {

void MapUncertainty::add_keyframe(std::size_t first_point, const Eigen::Matrix3d& covariance) {
  first_points_.push_back(first_point);
  covariances_.push_back(covariance);
}

Eigen::Matrix3d MapUncertainty::of_points(const std::vector<std::size_t>& map_indices) const {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  std::size_t counted = 0;
  for (const std::size_t index : map_indices) {
    // The last keyframe that starts at or before the point (a keyframe that added nothing
    // shares its start with the next one, which then owns the point).
    const auto after = std::upper_bound(first_points_.begin(), first_points_.end(), index);
    if (after == first_points_.begin()) continue;
    sum += covariances_[static_cast<std::size_t>(after - first_points_.begin()) - 1];
    ++counted;
  }
  return counted == 0 ? sum : Eigen::Matrix3d(sum / double(counted));
}

}  // namespace uavslam
