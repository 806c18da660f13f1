#include "core/extensions/FloorLevel.hpp"

#include <cmath>

namespace uavslam {

std::optional<HeightFix> FloorLevel::add(double stamp, double z, const FloorSighting& floor) {
  const double level = z - floor.below;
  if (!settled_) {
    if (!start_) start_ = stamp;
    if (stamp - *start_ < window_ || n_ == 0) {
      ++n_;
      sum_ += level;
      variances_ += floor.variance;
      return std::nullopt;
    }
    settled_ = true;
  }
  if (std::abs(level - this->level()) > gate_) return std::nullopt;
  return HeightFix{this->level() + floor.below,
                   floor.variance + flatness_ * flatness_ + level_variance()};
}

// The mean of n levels, each known to its sighting's variance: sum(var) / n^2.
double FloorLevel::level_variance() const {
  return n_ > 0 ? variances_ / (double(n_) * double(n_)) : 0.0;
}

}  // namespace uavslam
