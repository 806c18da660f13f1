// How well the map itself is placed (beyond the seed). A match fixes the vehicle relative to the
// map points it paired with, and those points are only as well placed as the keyframe that added
// them was. So each keyframe keeps the covariance its pose had when it joined the map, and a
// match inherits its pairs' keyframes' covariances, each in the directions its pairs fixed. By
// linear propagation through the normal equations (H t = sum_i J_i r_i), a shift e_k of keyframe
// k's points moves the match by W_k e_k, W_k = H^-1 H_k (H_k: the information of k's pairs, H
// their sum, so the W_k sum to I). Keyframes on one exploration chain share most of their error,
// so they are taken as fully correlated, each with its covariance's square root S_k:
//   Sigma_map = L L^T,   L = sum_k W_k S_k
// One keyframe gives its own covariance; a door edge seen only in a drifted keyframe gives that
// keyframe's along the corridor, however many wall pairs the anchor holds. The first keyframe
// anchors the map's frame (zero). Exploring, a keyframe pairs with the last few and the
// covariance grows like a random walk; back in a known place the old keyframes' smaller one
// returns. It is the spanning tree of a pose graph's marginals (Olson's Dijkstra projection),
// without the loop edges that only a back end adds.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "core/Correspondences.hpp"

namespace uavslam {

class MapUncertainty {
 public:
  // The keyframe whose points start at map index first_point, and its pose's covariance (m^2).
  void add_keyframe(std::size_t first_point, const Eigen::Matrix3d& covariance);

  // The same keyframes, in the same order, now starting at these map indices (the map was
  // rebuilt); throws std::invalid_argument for another count.
  void move_keyframes(const std::vector<std::size_t>& first_points);

  // Sigma_map above for the pairs (their map_index, and the information pair_information gives
  // them); zero when no pair holds information.
  Eigen::Matrix3d of_match(const Correspondences& pairs) const;

 private:
  // The keyframe that added map point `index`; none before the first keyframe's points.
  std::optional<std::size_t> keyframe_of(std::size_t index) const;

  std::vector<std::size_t> first_points_;  // ascending
  std::vector<Eigen::Matrix3d> roots_;     // S_k: the covariances' symmetric square roots
};

}  // namespace uavslam
