#include "core/extensions/MapUncertainty.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/extensions/ScanInformation.hpp"

namespace uavslam {
namespace {

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

// perp(v): how a point at v from a keyframe's position moves per radian the keyframe turns.
Vec3 perp(const Vec3& v) {
  return {-v.y(), v.x(), 0.0};
}

}  // namespace

void MapUncertainty::add_keyframe(std::size_t first_point, const Vec3& position,
                                  const Eigen::Matrix4d& own_covariance,
                                  const Eigen::Vector4d& drift, const Eigen::Vector4d& applied,
                                  const CorrelatedError& inherited) {
  CorrelatedError error = inherited;
  error.add_noise(first_points_.size(), own_covariance);
  error.prune(kSourcesKept);
  errors_.push_back(std::move(error));
  first_points_.push_back(first_point);
  positions_.push_back(position);
  drifts_.push_back(drift);
  applied_.push_back(applied);
}

void MapUncertainty::turn(std::size_t k, double turn, double rate) {
  if (k >= applied_.size()) return;
  applied_[k](3) += turn;
  applied_[k].head<3>() = drifts_[k].head<3>() * rate;
}

void MapUncertainty::move_keyframes(const std::vector<std::size_t>& first_points,
                                    const std::vector<Vec3>& positions) {
  if (first_points.size() != first_points_.size() || positions.size() != positions_.size()) {
    throw std::invalid_argument("MapUncertainty: " + std::to_string(first_points.size()) +
                                " keyframes (" + std::to_string(positions.size()) +
                                " positions) moved of " + std::to_string(first_points_.size()));
  }
  first_points_ = first_points;
  positions_ = positions;
}

// The last keyframe that starts at or before the point (a keyframe that added nothing shares its
// start with the next one, which then owns the point).
std::optional<std::size_t> MapUncertainty::keyframe_of(std::size_t index) const {
  const auto after = std::upper_bound(first_points_.begin(), first_points_.end(), index);
  if (after == first_points_.begin()) return std::nullopt;
  return static_cast<std::size_t>(after - first_points_.begin()) - 1;
}

// Each keyframe's pairs, H_k and sum_i H_i perp(d_i - p_k), and H.
MapUncertainty::Grouped MapUncertainty::by_keyframe(const Correspondences& pairs) const {
  Grouped grouped;
  for (std::size_t i = 0; i < pairs.map_index.size(); ++i) {
    const std::optional<std::size_t> k = keyframe_of(pairs.map_index[i]);
    const Eigen::Matrix3d information = pair_information(pairs, i);
    if (!k || information.isZero()) continue;
    KeyframePairs& own = grouped.keyframes[*k];
    own.information += information;
    own.turn += information * perp(pairs.map[i] - positions_[*k]);
    grouped.total += information;
  }
  return grouped;
}

MapError MapUncertainty::of_match(const Correspondences& pairs, const Vec3& position,
                                  const Eigen::Vector2d& scan_drift) const {
  const Grouped grouped = by_keyframe(pairs);
  MapError error;
  if (grouped.keyframes.empty()) return error;
  const double horizontal = grouped.total.topLeftCorner<2, 2>().trace();
  const Eigen::Matrix3d inverse = pseudo_inverse(grouped.total);
  Vec3 lever = Vec3::Zero();  // sum_i H_i perp(d_i - p)
  for (const auto& [k, own] : grouped.keyframes) {
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    A.topLeftCorner<3, 3>() = inverse * own.information;
    A.topRightCorner<3, 1>() = inverse * own.turn;
    A(3, 3) = horizontal > 0.0 ? own.information.topLeftCorner<2, 2>().trace() / horizontal : 0.0;
    error.error.add(A, errors_[k]);
    error.drift += A * drifts_[k];
    error.applied += A * applied_[k];
    lever += own.turn + own.information * perp(positions_[k] - position);
  }
  error.error.prune(kSourcesKept);
  // The scan's own heading error turns its points about the vehicle: the match moves by -g eps.
  const Vec3 g = inverse * lever;
  error.drift.head<3>() -= g * scan_drift(0);
  error.applied.head<3>() -= g * scan_drift(1);
  return error;
}

std::vector<std::pair<std::size_t, double>> MapUncertainty::heading_shares(
    const Correspondences& pairs) const {
  const Grouped grouped = by_keyframe(pairs);
  const double horizontal = grouped.total.topLeftCorner<2, 2>().trace();
  std::vector<std::pair<std::size_t, double>> shares;
  if (horizontal <= 0.0) return shares;
  for (const auto& [k, own] : grouped.keyframes) {
    const double share = own.information.topLeftCorner<2, 2>().trace() / horizontal;
    if (share > 0.0) shares.emplace_back(k, share);
  }
  return shares;
}

}  // namespace uavslam
