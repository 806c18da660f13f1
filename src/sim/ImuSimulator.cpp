#include "sim/ImuSimulator.hpp"

#include <algorithm>

#include "core/Angles.hpp"
#include "sim/SeedMixing.hpp"

namespace uavslam::sim {

namespace {

// The rotation exp(v) of a rotation vector v (axis * angle).
Eigen::Quaterniond rotation_from_vector(const Vec3& v) {
  const double angle = v.norm();
  if (angle == 0.0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle));
}

}  // namespace

Eigen::Quaterniond heading_drift_at(const ImuSpec& spec, const Trajectory& trajectory, double t) {
  // The rate in force over each stretch, integrated up to t.
  double degrees = 0.0;
  double from = trajectory.start_time();
  double rate = spec.yaw_drift_deg_per_min;
  for (const DriftChange& change : spec.yaw_drift_changes) {
    const double until = std::min(t, trajectory.start_time() + change.t);
    if (until > from) degrees += rate * (until - from) / 60.0;
    from = std::max(from, until);
    rate = change.deg_per_min;
  }
  if (t > from) degrees += rate * (t - from) / 60.0;
  return Eigen::Quaterniond(Eigen::AngleAxisd(deg_to_rad(degrees), Vec3::UnitZ()));
}

ImuSimulator::ImuSimulator(const ImuSpec& spec, std::uint64_t seed)
    : spec_(spec), random_(mix_seed(seed, kImuStream)) {}

ImuSample ImuSimulator::sample_at(const Trajectory& trajectory, double t) {
  const Pose truth = trajectory.pose_at(t);
  // Heading drift turns the reported attitude about the world vertical.
  const Eigen::Quaterniond drift = heading_drift_at(spec_, trajectory, truth.stamp);
  const Vec3 attitude_noise = deg_to_rad(spec_.orientation_noise_std_deg) *
                              standard_normal_vector(random_, standard_normal_);
  const Vec3 gyro_noise = spec_.gyro_noise_std * standard_normal_vector(random_, standard_normal_);
  const Vec3 accel_noise =
      spec_.accel_noise_std * standard_normal_vector(random_, standard_normal_);

  ImuSample sample;
  sample.stamp = t;
  sample.orientation =
      (drift * truth.orientation * rotation_from_vector(attitude_noise)).normalized();
  sample.angular_velocity = trajectory.angular_velocity_at(t) + gyro_noise;
  // An accelerometer measures specific force: what the thrust does beyond cancelling gravity.
  const Vec3 specific_force_world = trajectory.acceleration_at(t) + kGravity * Vec3::UnitZ();
  sample.linear_acceleration =
      truth.orientation.conjugate() * specific_force_world + spec_.accel_bias + accel_noise;
  return sample;
}

}  // namespace uavslam::sim
