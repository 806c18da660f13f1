// Is the reported covariance consistent with the error? The normalised estimation error squared
// (NEES, Bar-Shalom, Li & Kirubarajan 2001, sec. 5.4):
//   epsilon = e^T Sigma^-1 e,   e = estimate - truth
// For a consistent estimator its mean over a run is the state's dimension; well under means the
// covariance is too cautious, well over that it is too confident.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "core/Types.hpp"

namespace uavslam::eval {

struct Nees {
  double value = 0.0;
  int dimension = 0;  // the axes the covariance states (a zero variance: not estimated)
};

// Over the axes with a positive variance; none when there are none or the block is singular.
std::optional<Nees> nees(const Vec3& error, const Eigen::Matrix3d& covariance);

struct NeesSummary {
  std::size_t count = 0;
  double mean = 0.0;
  double mean_dimension = 0.0;  // the samples' mean dimension: the mean a consistent run has
};

NeesSummary summarize(const std::vector<Nees>& samples);

}  // namespace uavslam::eval
