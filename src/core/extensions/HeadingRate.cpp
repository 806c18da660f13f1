#include "core/extensions/HeadingRate.hpp"

#include <algorithm>
#include <cmath>

namespace uavslam {
namespace {

// A drift is followed once the checks show it beyond three of its standard errors.
constexpr double kSignificance = 3.0;
// Checks before a rate is believed at all: the residual variance of a line through a few of them
// is itself a guess (a take-off's first three put 7 degrees a minute on a steady source).
constexpr std::size_t kMinChecks = 30;

}  // namespace

void HeadingRate::add_check(double disagreement, double span, double applied) {
  if (span <= 0.0) return;
  const double m = disagreement + applied;
  ++n_;
  t_ += span;
  m_ += m;
  tt_ += span * span;
  tm_ += span * m;
  mm_ += m * m;
}

double HeadingRate::rate() const {
  if (prior_sigma_ <= 0.0 || n_ < kMinChecks) return 0.0;
  const double n = double(n_);
  const double s_tt = std::max(0.0, tt_ - t_ * t_ / n);
  const double s_tm = tm_ - t_ * m_ / n;
  const double s_mm = std::max(0.0, mm_ - m_ * m_ / n);
  // The residual variance of the line m = c + r dt fitted without the prior.
  const double unexplained = s_tt > 0.0 ? s_mm - s_tm * s_tm / s_tt : s_mm;
  const double noise = std::max(unexplained, 0.0) / (n - 2.0);  // sigma_d^2
  const double prior = noise / (prior_sigma_ * prior_sigma_);
  if (s_tt + prior <= 0.0) return 0.0;
  const double r = s_tm / (s_tt + prior);
  const double sigma = std::sqrt(noise / (s_tt + prior));
  return std::abs(r) > kSignificance * sigma ? r : 0.0;
}

}  // namespace uavslam
