#include "sim/VelocitySimulator.hpp"

#include "sim/ImuSimulator.hpp"
#include "sim/SeedMixing.hpp"

namespace uavslam::sim {

VelocitySimulator::VelocitySimulator(const VelocitySpec& spec, const ImuSpec& imu,
                                     std::uint64_t seed)
    : spec_(spec), imu_(imu), random_(mix_seed(seed, kVelocityStream)) {}

VelocitySample VelocitySimulator::sample_at(const Trajectory& trajectory, double t) {
  const Vec3 noise = spec_.noise_std * standard_normal_vector(random_, standard_normal_);
  VelocitySample sample;
  sample.stamp = t;
  sample.velocity = heading_drift_at(imu_, trajectory, t) * trajectory.velocity_at(t) + noise;
  sample.covariance = spec_.noise_std * spec_.noise_std * Eigen::Matrix3d::Identity();
  return sample;
}

}  // namespace uavslam::sim
