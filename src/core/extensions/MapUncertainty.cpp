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
template <typename Matrix>
Matrix pseudo_inverse(const Matrix& information) {
  const Eigen::SelfAdjointEigenSolver<Matrix> solver(information);
  const double largest = solver.eigenvalues().maxCoeff();
  Eigen::VectorXd inverse = Eigen::VectorXd::Zero(information.rows());
  for (Eigen::Index i = 0; i < information.rows(); ++i) {
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
MapUncertainty::Grouped MapUncertainty::by_keyframe(const Correspondences& pairs,
                                                    const Vec3& position) const {
  Grouped grouped;
  for (std::size_t i = 0; i < pairs.map_index.size(); ++i) {
    const std::optional<std::size_t> k = keyframe_of(pairs.map_index[i]);
    const Eigen::Matrix4d joint = pair_joint_information(pairs, i, position);
    const Eigen::Matrix3d information = joint.topLeftCorner<3, 3>();
    if (!k || information.isZero()) continue;
    KeyframePairs& own = grouped.keyframes[*k];
    own.information += information;
    own.turn += information * perp(pairs.map[i] - positions_[*k]);
    own.joint += joint;
    grouped.total += information;
    grouped.joint += joint;
  }
  return grouped;
}

MapError MapUncertainty::of_match(const Correspondences& pairs, const Vec3& position,
                                  const Eigen::Vector2d& scan_drift, bool with_yaw) const {
  const Grouped grouped = by_keyframe(pairs, position);
  MapError error;
  if (grouped.keyframes.empty()) return error;
  if (with_yaw) {
    joint_match(grouped, position, error);
  } else {
    translation_match(grouped, position, scan_drift, error);
  }
  error.error.prune(kSourcesKept);
  return error;
}

// The match estimated its translation only: A_k = [W_k g_k; 0 s_k] (the header's).
void MapUncertainty::translation_match(const Grouped& grouped, const Vec3& position,
                                       const Eigen::Vector2d& scan_drift, MapError& error) const {
  const double horizontal = grouped.total.topLeftCorner<2, 2>().trace();
  const Eigen::Matrix3d inverse = pseudo_inverse(grouped.total);
  Vec3 lever = Vec3::Zero();  // sum_i H_i perp(d_i - p)
  for (const auto& [k, own] : grouped.keyframes) {
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    A.topLeftCorner<3, 3>() = inverse * own.information;
    A.topRightCorner<3, 1>() = inverse * own.turn;
    A(3, 3) = horizontal > 0.0 ? own.information.topLeftCorner<2, 2>().trace() / horizontal : 0.0;
    add_keyframe_share(k, A, error);
    lever += own.turn + own.information * perp(positions_[k] - position);
  }
  // The scan's own heading error turns its points about the vehicle: the match moves by -g eps.
  const Vec3 g = inverse * lever;
  error.drift.head<3>() -= g * scan_drift(0);
  error.applied.head<3>() -= g * scan_drift(1);
}

// The match estimated its heading too: keyframe k's error (e_k, eps_k) moves its points by
//   e_k + eps_k perp(d_i - p_k) = [e_k + eps_k perp(p - p_k)] + eps_k perp(d_i - p),
// a translation and a turn about the vehicle, both of which the match follows (J_i^T u_k is the
// pairs' residual, J_i ScanInformation's Jacobian), so over (x, y, z, yaw)
//   A_k = H4^-1 H4_k M_k,   M_k = [I perp(p - p_k); 0 1]
// (H4: the pairs' information over the four, H4_k keyframe k's share). A keyframe turned about
// its own position moves a match near it by its lever arm to the vehicle, not to the walls.
void MapUncertainty::joint_match(const Grouped& grouped, const Vec3& position,
                                 MapError& error) const {
  const Eigen::Matrix4d inverse = pseudo_inverse(grouped.joint);
  for (const auto& [k, own] : grouped.keyframes) {
    Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
    M.topRightCorner<3, 1>() = perp(position - positions_[k]);
    add_keyframe_share(k, inverse * own.joint * M, error);
  }
}

void MapUncertainty::add_keyframe_share(std::size_t k, const Eigen::Matrix4d& A,
                                        MapError& error) const {
  error.error.add(A, errors_[k]);
  error.drift += A * drifts_[k];
  error.applied += A * applied_[k];
}

std::vector<std::pair<std::size_t, double>> MapUncertainty::heading_shares(
    const Correspondences& pairs) const {
  // The shares read the pairs' horizontal information only, not the turn about a position.
  const Grouped grouped = by_keyframe(pairs, Vec3::Zero());
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
