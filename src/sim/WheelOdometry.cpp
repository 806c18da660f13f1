#include "sim/WheelOdometry.hpp"

#include <cmath>
#include <random>

#include "sim/SeedMixing.hpp"

namespace uavslam::sim {

std::vector<PlanarPose> wheel_odometry(const std::vector<Pose>& truth,
                                       const WheelOdometrySpec& spec, std::uint64_t seed) {
  std::vector<PlanarPose> odometry;
  if (truth.empty()) return odometry;
  odometry.reserve(truth.size());
  std::mt19937_64 random(mix_seed(seed, kOdometryStream));
  std::normal_distribution<double> standard_normal;
  odometry.push_back(planar_pose(truth.front()));
  for (std::size_t i = 1; i < truth.size(); ++i) {
    // The true step in the body frame it starts from.
    const PlanarPose step = motion_between(planar_pose(truth[i - 1]), planar_pose(truth[i]));
    const double length = std::hypot(step.x, step.y);
    const double k_t = spec.translation_noise * std::sqrt(length);
    const double k_a = std::sqrt(spec.turn_noise * spec.turn_noise * std::abs(step.theta) +
                                 spec.turn_per_metre_noise * spec.turn_per_metre_noise * length);
    // Separate statements: the draws keep their order.
    const double n_forward = k_t * standard_normal(random);
    const double n_sideways = k_t * standard_normal(random);
    const double n_turn = k_a * standard_normal(random);
    const double scale = 1.0 + spec.translation_scale_error;
    odometry.push_back(
        compose(odometry.back(), {scale * step.x + n_forward, scale * step.y + n_sideways,
                                  (1.0 + spec.turn_scale_error) * step.theta + n_turn}));
  }
  return odometry;
}

}  // namespace uavslam::sim
