#include "core/extensions/HeadingRate.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/Angles.hpp"

namespace uavslam {
namespace {

// A drift is followed once the checks show it beyond three of its standard errors.
constexpr double kSignificance = 3.0;
// The keyframes made before are turned by it only beyond five: the test is made again at every
// keyframe, hundreds of looks a flight, and at three a steady source's noise passes it now and
// then for a few checks (demo.yaml seed 14: 3.1 standard errors at its 64th check). Following
// such a rate for a while costs little; turning the map on it costs the flight (0.026 -> 0.046 m).
constexpr double kTurnSignificance = 5.0;
// Checks before a rate is believed at all: the residual variance of a line through a few of them
// is itself a guess (a take-off's first three put 7 degrees a minute on a steady source).
constexpr std::size_t kMinChecks = 30;
// A line's standard error needs a residual: three checks.
constexpr std::size_t kMinChecksForLine = 3;

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
  const std::optional<Fit> line = followed_fit();
  return line && std::abs(line->rate) > kSignificance * line->sigma ? line->rate : 0.0;
}

std::optional<HeadingRate::Fit> HeadingRate::fit(std::size_t min_checks) const {
  if (n_ < min_checks) return std::nullopt;
  const double n = double(n_);
  const double s_tt = std::max(0.0, tt_ - t_ * t_ / n);
  const double s_tm = tm_ - t_ * m_ / n;
  const double s_mm = std::max(0.0, mm_ - m_ * m_ / n);
  // The residual variance of the line m = c + r dt fitted without the prior.
  const double unexplained = s_tt > 0.0 ? s_mm - s_tm * s_tm / s_tt : s_mm;
  const double noise = std::max(unexplained, 0.0) / (n - 2.0);  // sigma_d^2
  const double prior = prior_sigma_ > 0.0 ? noise / (prior_sigma_ * prior_sigma_) : 0.0;
  if (s_tt + prior <= 0.0) return std::nullopt;
  return Fit{s_tm / (s_tt + prior), std::sqrt(noise / (s_tt + prior))};
}

// Followed and turned by only with a prior, and from kMinChecks on.
std::optional<HeadingRate::Fit> HeadingRate::followed_fit() const {
  if (prior_sigma_ <= 0.0) return std::nullopt;
  return fit(kMinChecks);
}

std::vector<double> HeadingRate::turns(const std::vector<double>& stamps,
                                       const std::vector<double>& corrections) const {
  const std::optional<Fit> line = followed_fit();
  const std::size_t n = std::min(stamps.size(), corrections.size());
  if (!line || std::abs(line->rate) <= kTurnSignificance * line->sigma) {
    return std::vector<double>(n, 0.0);
  }
  std::vector<double> turns;
  for (std::size_t k = 0; k < n; ++k) {
    turns.push_back(wrap_angle(line->rate * (stamps[k] - stamps.front()) -
                               (corrections[k] - corrections.front())));
  }
  return turns;
}

HeadingRate::Estimate HeadingRate::estimate() const {
  const std::optional<Fit> line = fit(kMinChecksForLine);
  if (!line) return {0.0, prior_sigma_ * prior_sigma_};
  return {line->rate, line->sigma * line->sigma};
}

}  // namespace uavslam
