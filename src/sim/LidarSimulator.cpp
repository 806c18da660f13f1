#include "sim/LidarSimulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sensor/LidarGeometry.hpp"
#include "sim/SeedMixing.hpp"

namespace uavslam::sim {

LidarSimulator::LidarSimulator(const LidarSpec& spec, const World& world, std::uint64_t seed)
    : world_(&world),
      geometry_(make_scan_geometry(spec)),
      range_noise_std_(spec.range_noise_std),
      random_(mix_seed(seed, kLidarStream)) {}

float LidarSimulator::range_of(const Eigen::Isometry3d& sensor_in_world, const Vec3& direction,
                               double fired) {
  const double hit =
      world_->cast_ray(sensor_in_world.translation(), sensor_in_world.linear() * direction,
                       geometry_->max_range, fired);
  // Draw for every beam (hit or not) so one beam's miss does not shift the others' noise.
  const double noisy = hit + range_noise_std_ * standard_normal_(random_);
  const bool valid = std::isfinite(hit) && noisy <= geometry_->max_range;
  return valid ? static_cast<float>(std::max(noisy, 0.0)) : std::numeric_limits<float>::infinity();
}

Scan LidarSimulator::scan_at(const Pose& body_pose, double stamp, std::uint64_t sequence) {
  const Eigen::Isometry3d sensor_in_world = body_pose.isometry() * geometry_->mount;
  Scan scan;
  scan.stamp = stamp;
  scan.sequence = sequence;
  scan.geometry = geometry_;
  scan.ranges.reserve(geometry_->directions.size());
  for (const Vec3& direction : geometry_->directions) {
    scan.ranges.push_back(range_of(sensor_in_world, direction, stamp));
  }
  return scan;
}

Scan LidarSimulator::scan_along(const Trajectory& trajectory, double taken, double stamp,
                                std::uint64_t sequence) {
  const std::size_t beams = geometry_->directions.size();
  if (geometry_->fire_times.empty()) {
    Scan scan = scan_at(trajectory.pose_at(taken), taken, sequence);
    scan.stamp = stamp;
    return scan;
  }
  Scan scan;
  scan.stamp = stamp;
  scan.sequence = sequence;
  scan.geometry = geometry_;
  scan.ranges.reserve(beams);
  for (std::size_t i = 0; i < beams; ++i) {
    const double fired = taken + geometry_->fire_times[i];
    const Eigen::Isometry3d sensor_in_world =
        trajectory.pose_at(fired).isometry() * geometry_->mount;
    scan.ranges.push_back(range_of(sensor_in_world, geometry_->directions[i], fired));
  }
  return scan;
}

}  // namespace uavslam::sim
