#include "core/extensions/MapUncertainty.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

#include "core/extensions/ScanInformation.hpp"

namespace uavslam {
namespace {

// The symmetric square root of a covariance (its negative rounding errors taken as zero).
Eigen::Matrix3d square_root(const Eigen::Matrix3d& covariance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d roots = solver.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return solver.eigenvectors() * roots.asDiagonal() * solver.eigenvectors().transpose();
}

// H^-1 over the directions the pairs hold information in (H^+: a blind direction gets no weight).
Eigen::Matrix3d pseudo_inverse(const Eigen::Matrix3d& information) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(information);
  const double largest = solver.eigenvalues().maxCoeff();
  Eigen::Vector3d inverse = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (solver.eigenvalues()(i) > 1e-9 * largest) inverse(i) = 1.0 / solver.eigenvalues()(i);
  }
  return solver.eigenvectors() * inverse.asDiagonal() * solver.eigenvectors().transpose();
}

}  // namespace

void MapUncertainty::add_keyframe(std::size_t first_point, const Eigen::Matrix3d& covariance) {
  first_points_.push_back(first_point);
  roots_.push_back(square_root(covariance));
}

void MapUncertainty::move_keyframes(const std::vector<std::size_t>& first_points) {
  if (first_points.size() != first_points_.size()) {
    throw std::invalid_argument("MapUncertainty: " + std::to_string(first_points.size()) +
                                " keyframes moved of " + std::to_string(first_points_.size()));
  }
  first_points_ = first_points;
}

// The last keyframe that starts at or before the point (a keyframe that added nothing shares its
// start with the next one, which then owns the point).
std::optional<std::size_t> MapUncertainty::keyframe_of(std::size_t index) const {
  const auto after = std::upper_bound(first_points_.begin(), first_points_.end(), index);
  if (after == first_points_.begin()) return std::nullopt;
  return static_cast<std::size_t>(after - first_points_.begin()) - 1;
}

Eigen::Matrix3d MapUncertainty::of_match(const Correspondences& pairs) const {
  std::map<std::size_t, Eigen::Matrix3d> by_keyframe;  // H_k
  Eigen::Matrix3d total = Eigen::Matrix3d::Zero();     // H
  for (std::size_t i = 0; i < pairs.map_index.size(); ++i) {
    const std::optional<std::size_t> k = keyframe_of(pairs.map_index[i]);
    const Eigen::Matrix3d information = pair_information(pairs, i);
    if (!k || information.isZero()) continue;
    by_keyframe.try_emplace(*k, Eigen::Matrix3d::Zero()).first->second += information;
    total += information;
  }
  if (by_keyframe.empty()) return Eigen::Matrix3d::Zero();
  const Eigen::Matrix3d inverse = pseudo_inverse(total);
  Eigen::Matrix3d L = Eigen::Matrix3d::Zero();
  for (const auto& [k, information] : by_keyframe) L += inverse * information * roots_[k];
  return L * L.transpose();
}

}  // namespace uavslam
