#include "sim/WheelOdometry.hpp"

#include <cmath>
#include <random>

#include "core/Angles.hpp"
#include "core/Heading.hpp"
#include "sim/SeedMixing.hpp"

namespace uavslam::sim {

PlanarPose planar_pose(const Pose& pose) {
  return {pose.position.x(), pose.position.y(), heading_of(pose.orientation)};
}

std::vector<PlanarPose> wheel_odometry(const std::vector<Pose>& truth,
                                       const WheelOdometrySpec& spec, std::uint64_t seed) {
  std::vector<PlanarPose> odometry;
  if (truth.empty()) return odometry;
  odometry.reserve(truth.size());
  std::mt19937_64 random(mix_seed(seed, kOdometryStream));
  std::normal_distribution<double> standard_normal;
  PlanarPose now = planar_pose(truth.front());
  odometry.push_back(now);
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const PlanarPose a = planar_pose(truth[i - 1]);
    const PlanarPose b = planar_pose(truth[i]);
    // The true step in a's body frame.
    const double c = std::cos(a.theta), s = std::sin(a.theta);
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double forward = c * dx + s * dy, sideways = -s * dx + c * dy;
    const double turn = wrap_angle(b.theta - a.theta);
    const double length = std::hypot(forward, sideways);
    const double k_t = spec.translation_noise * std::sqrt(length);
    const double k_a = std::sqrt(spec.turn_noise * spec.turn_noise * std::abs(turn) +
                                 spec.turn_per_metre_noise * spec.turn_per_metre_noise * length);
    // Separate statements: the draws keep their order.
    const double n_forward = k_t * standard_normal(random);
    const double n_sideways = k_t * standard_normal(random);
    const double n_turn = k_a * standard_normal(random);
    const double read_forward = (1.0 + spec.translation_scale_error) * forward + n_forward;
    const double read_sideways = (1.0 + spec.translation_scale_error) * sideways + n_sideways;
    const double read_turn = (1.0 + spec.turn_scale_error) * turn + n_turn;
    now.x += std::cos(now.theta) * read_forward - std::sin(now.theta) * read_sideways;
    now.y += std::sin(now.theta) * read_forward + std::cos(now.theta) * read_sideways;
    now.theta = wrap_angle(now.theta + read_turn);
    odometry.push_back(now);
  }
  return odometry;
}

}  // namespace uavslam::sim
