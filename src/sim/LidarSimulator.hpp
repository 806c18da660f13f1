// A simulated LiDAR: ray-casts every beam of its geometry into the world and adds range noise.
#pragma once

#include <cstdint>
#include <memory>
#include <random>

#include "core/Types.hpp"
#include "sim/Scenario.hpp"
#include "sim/Trajectory.hpp"
#include "sim/World.hpp"

namespace uavslam::sim {

class LidarSimulator {
 public:
  // Keeps a reference to `world`, which must outlive the simulator.
  LidarSimulator(const LidarSpec& spec, const World& world, std::uint64_t seed);
  LidarSimulator(const LidarSpec&, const World&&, std::uint64_t) = delete;  // would dangle

  std::shared_ptr<const ScanGeometry> geometry() const { return geometry_; }

  // One sweep from the sensor at body_pose * mount, taken at `stamp` (where the people are). A
  // miss, or a noisy range beyond max_range, reads +infinity. Consumes one noise draw per beam, so
  // the stream does not depend on the hits.
  Scan scan_at(const Pose& body_pose, double stamp, std::uint64_t sequence);

  // One sweep of a vehicle flying `trajectory`, its first beam at `taken`: each beam from where
  // the vehicle was when it fired (the geometry's fire_times, from the spec's sweep_seconds; all
  // from `taken` without a sweep, as scan_at).
  Scan scan_along(const Trajectory& trajectory, double taken, double stamp, std::uint64_t sequence);

 private:
  const World* world_;
  std::shared_ptr<const ScanGeometry> geometry_;
  double range_noise_std_;

  // One beam's noisy range from the sensor at `sensor_in_world`, fired `fired` s into the flight
  // (one noise draw, hit or not).
  float range_of(const Eigen::Isometry3d& sensor_in_world, const Vec3& direction, double fired);
  std::mt19937_64 random_;
  std::normal_distribution<double> standard_normal_{0.0, 1.0};
};

}  // namespace uavslam::sim
