#include "core/extensions/CorrelatedError.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>

namespace uavslam {
namespace {

// The symmetric square root of a covariance (its negative rounding errors taken as zero).
Eigen::Matrix4d square_root(const Eigen::Matrix4d& covariance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> solver(covariance);
  const Eigen::Vector4d roots = solver.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return solver.eigenvectors() * roots.asDiagonal() * solver.eigenvectors().transpose();
}

bool before(const std::pair<std::size_t, Eigen::Matrix4d>& term, std::size_t source) {
  return term.first < source;
}

}  // namespace

void CorrelatedError::add_noise(std::size_t source, const Eigen::Matrix4d& covariance) {
  CorrelatedError noise;
  noise.terms_.emplace_back(source, square_root(covariance));
  add(Eigen::Matrix4d::Identity(), noise);
}

void CorrelatedError::add(const Eigen::Matrix4d& A, const CorrelatedError& other) {
  if (other.terms_.empty()) return;
  std::vector<std::pair<std::size_t, Eigen::Matrix4d>> merged;
  merged.reserve(terms_.size() + other.terms_.size());
  auto mine = terms_.begin();
  for (const auto& [source, C] : other.terms_) {
    while (mine != terms_.end() && mine->first < source) merged.push_back(*mine++);
    if (mine != terms_.end() && mine->first == source) {
      merged.emplace_back(source, mine->second + A * C);
      ++mine;
    } else {
      merged.emplace_back(source, A * C);
    }
  }
  merged.insert(merged.end(), mine, terms_.end());
  terms_ = std::move(merged);
}

void CorrelatedError::forget(int axis) {
  for (auto& term : terms_) term.second.row(axis).setZero();
}

void CorrelatedError::prune(std::size_t kept) {
  const auto common = std::lower_bound(terms_.begin(), terms_.end(), kCommon, before);
  const std::size_t own = static_cast<std::size_t>(common - terms_.begin());
  if (own <= kept) return;
  std::vector<std::pair<double, std::size_t>> sizes;  // (norm, index), largest first
  for (std::size_t i = 0; i < own; ++i) sizes.emplace_back(terms_[i].second.norm(), i);
  std::nth_element(sizes.begin(), sizes.begin() + static_cast<std::ptrdiff_t>(kept), sizes.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<bool> keep(own, false);
  for (std::size_t i = 0; i < kept; ++i) keep[sizes[i].second] = true;
  Eigen::Matrix4d folded = Eigen::Matrix4d::Zero();
  if (common != terms_.end()) folded = common->second * common->second.transpose();
  std::vector<std::pair<std::size_t, Eigen::Matrix4d>> pruned;
  pruned.reserve(kept + 1);
  for (std::size_t i = 0; i < own; ++i) {
    if (keep[i]) {
      pruned.push_back(terms_[i]);
    } else {
      folded += terms_[i].second * terms_[i].second.transpose();
    }
  }
  pruned.emplace_back(kCommon, square_root(folded));
  terms_ = std::move(pruned);
}

Eigen::Matrix4d CorrelatedError::covariance() const {
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();
  for (const auto& term : terms_) covariance += term.second * term.second.transpose();
  return covariance;
}

}  // namespace uavslam
