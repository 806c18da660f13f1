// How well the map itself is placed (beyond the seed). A match fixes the vehicle relative to the
// map points it paired with, and those points are only as well placed as the keyframe that added
// them was. So each keyframe keeps the covariance its pose had when it joined the map, and a
// match inherits its pairs' keyframes' covariances, averaged over the pairs:
//   Sigma_absolute = (1/n) sum_i Sigma_keyframe(d_i) + Sigma_match
// One keyframe's points share one error (its pose's), so they count as one; the mean of the
// variances lies between keyframes taken as independent (which would shrink it with their
// number) and as one. The first keyframe anchors the map's frame (zero). Exploring, a keyframe
// pairs with the last few and the covariance grows like a random walk; back in a known place the
// old keyframes' smaller one returns. It is the spanning tree of a pose graph's marginals
// (Olson's Dijkstra projection), without the loop edges that only a back end adds.
#pragma once

#include <cstddef>
#include <vector>

#include "core/Types.hpp"

namespace uavslam {

class MapUncertainty {
 public:
  // The keyframe whose points start at map index first_point, and its pose's covariance (m^2).
  void add_keyframe(std::size_t first_point, const Eigen::Matrix3d& covariance);

  // The mean covariance of the keyframes that added the given map points; zero for none.
  Eigen::Matrix3d of_points(const std::vector<std::size_t>& map_indices) const;

 private:
  std::vector<std::size_t> first_points_;  // ascending
  std::vector<Eigen::Matrix3d> covariances_;
};

}  // namespace uavslam
