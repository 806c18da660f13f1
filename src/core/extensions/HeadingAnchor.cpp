#include "core/extensions/HeadingAnchor.hpp"

#include <algorithm>

#include "core/Angles.hpp"

namespace uavslam {

std::optional<double> HeadingAnchor::add(double stamp, double correction) {
  if (settled()) return std::nullopt;
  // The founding scan's correction is 0 by construction, n_0 - n_0: it only starts the clock.
  if (!start_) {
    start_ = stamp;
    return std::nullopt;
  }
  const double c = wrap_angle(correction);
  ++n_;
  sum_ += c;
  squares_ += c * c;
  if (stamp - *start_ < window_) return std::nullopt;
  settled_ = true;
  return -sum_ / double(n_);
}

double HeadingAnchor::sample_variance() const {
  if (n_ < 2) return 0.0;
  const double n = double(n_);
  return std::max(0.0, squares_ - sum_ * sum_ / n) / (n - 1.0);
}

double HeadingAnchor::variance() const {
  if (window_ <= 0.0) return 0.0;
  // Once turned, the corrections are no longer added: the mean's variance is theirs over N.
  return settled_ ? sample_variance() / double(n_) : sample_variance();
}

}  // namespace uavslam
