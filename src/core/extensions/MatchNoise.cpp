#include "core/extensions/MatchNoise.hpp"

#include <algorithm>

namespace uavslam {
namespace {

constexpr double kRate = 0.01;  // about a hundred matches to settle
constexpr double kCap = 9.0;    // d^2 / m: three sigmas

const Eigen::Matrix3d kHorizontal = Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal();
const Eigen::Matrix3d kVertical = Eigen::Vector3d(0.0, 0.0, 1.0).asDiagonal();

// One channel's step, given its part of the innovation measured with its current scale.
void learn(double& log_scale, const PriorDistance& distance) {
  if (distance.directions == 0 || !std::isfinite(distance.sigmas)) return;
  const double ratio = distance.sigmas * distance.sigmas / distance.directions;
  log_scale += kRate * (std::min(ratio, kCap) - 1.0);
}

}  // namespace

Eigen::Matrix3d MatchNoise::scaled(const Eigen::Matrix3d& match_covariance) const {
  const Eigen::Vector3d root(std::sqrt(horizontal_scale()), std::sqrt(horizontal_scale()),
                             std::sqrt(vertical_scale()));
  return root.asDiagonal() * match_covariance * root.asDiagonal();
}

void MatchNoise::add(const Vec3& correction, const Eigen::Matrix3d& observed,
                     const Eigen::Matrix3d& match_covariance,
                     const Eigen::Matrix3d& predicted_covariance) {
  const Eigen::Matrix3d S = scaled(match_covariance) + predicted_covariance;
  learn(log_horizontal_, distance_from_prior(correction, kHorizontal * observed * kHorizontal, S));
  learn(log_vertical_, distance_from_prior(correction, kVertical * observed * kVertical, S));
  ++added_;
}

bool MatchNoise::settled() const {
  return double(added_) * kRate >= 1.0;
}

}  // namespace uavslam
