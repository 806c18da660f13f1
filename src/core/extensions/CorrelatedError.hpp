// An error over (x, y, z, yaw) as the sum of the independent noises it came from (beyond the
// seed): e = sum_j C_j nu_j, nu_j ~ N(0, I_4), one noise per source j (a keyframe's match).
// Two errors made of the same noises are correlated exactly as far as they share them:
//   Cov(e, e') = sum_j C_j C'_j^T,   Cov(e) = sum_j C_j C_j^T
// so a match on many keyframes that each matched the ones before averages their own noises down
// while their common ancestry stays whole (linear propagation, as a pose graph's marginals would
// have it). Taking the keyframes as one shared error instead (L = sum_k A_k S_k) makes every
// keyframe's own noise a common one: a climb's keyframes each matched on all the earlier ones then
// chained their headings as a random walk, about twice the true spread after eight of them.
// To bound the cost, an error keeps its largest `kept` sources; the rest are folded into one
// common source shared by all errors (the shared-error assumption, for what is pruned).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace uavslam {

class CorrelatedError {
 public:
  // The source the pruned noises of every error are folded into.
  static constexpr std::size_t kCommon = std::numeric_limits<std::size_t>::max();
  // The source of the motion prior's error along the directions the scans left blind (a
  // corridor's axis) over the `stretch`-th blind stretch: the positions the prior carried through
  // one stretch err together (the same integrated velocity and bias), not by a fresh noise at
  // each keyframe; the next fix ends it. Counted down from kCommon, clear of the keyframes'.
  static constexpr std::size_t carried(std::size_t stretch) { return kCommon - 1 - stretch; }

  // Adds an independent noise of this covariance as source `source` (C = its symmetric root).
  void add_noise(std::size_t source, const Eigen::Matrix4d& covariance);
  // this += A other: the coefficients of a linear map of another error, source by source.
  void add(const Eigen::Matrix4d& A, const CorrelatedError& other);
  // The error along `axis` is no longer this one (measured absolutely from now on): row dropped.
  void forget(int axis);
  // Keeps the `kept` largest sources (Frobenius norm) and folds the rest into kCommon:
  //   C_common = sqrt(C_common C_common^T + sum_pruned C_j C_j^T)
  // (the covariance stays exact; only the pruned ones' correlations are taken as shared).
  void prune(std::size_t kept);

  Eigen::Matrix4d covariance() const;
  std::size_t sources() const { return terms_.size(); }

 private:
  std::vector<std::pair<std::size_t, Eigen::Matrix4d>> terms_;  // ascending source
};

}  // namespace uavslam
