#include "core/extensions/MatchNoise.hpp"

#include <algorithm>

namespace uavslam {
namespace {

constexpr double kRate = 0.01;  // about a hundred matches to settle
constexpr double kCap = 9.0;    // d^2 / m: three sigmas

}  // namespace

void MatchNoise::add(const PriorDistance& distance) {
  if (distance.directions == 0 || !std::isfinite(distance.sigmas)) return;
  const double ratio = distance.sigmas * distance.sigmas / distance.directions;
  log_scale_ = std::max(0.0, log_scale_ + kRate * (std::min(ratio, kCap) - 1.0));
}

}  // namespace uavslam
