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

Scan LidarSimulator::scan_at(const Pose& body_pose, double stamp, std::uint64_t sequence) {
  const Eigen::Isometry3d sensor_in_world = body_pose.isometry() * geometry_->mount;
  const Eigen::Matrix3d rotation = sensor_in_world.linear();
  const Vec3 origin = sensor_in_world.translation();
  const double max_range = geometry_->max_range;

  Scan scan;
  scan.stamp = stamp;
  scan.sequence = sequence;
  scan.geometry = geometry_;
  scan.ranges.reserve(geometry_->directions.size());
  for (const Vec3& direction : geometry_->directions) {
    const double hit = world_->cast_ray(origin, rotation * direction, max_range);
    // Draw for every beam (hit or not) so one beam's miss does not shift the others' noise.
    const double noisy = hit + range_noise_std_ * standard_normal_(random_);
    const bool valid = std::isfinite(hit) && noisy <= max_range;
    scan.ranges.push_back(valid ? static_cast<float>(std::max(noisy, 0.0))
                                : std::numeric_limits<float>::infinity());
  }
  return scan;
}

}  // namespace uavslam::sim
