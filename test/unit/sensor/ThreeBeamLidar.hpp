// A LiDAR whose three beams are easy to reason about, for the geometry and simulator tests.
#pragma once

#include "sensor/LidarSpec.hpp"

namespace uavslam::test {

// Three beams: to the right (-y), straight ahead (+x) and to the left (+y); no range noise.
inline LidarSpec three_beam_lidar() {
  LidarSpec spec;
  spec.beams = 3;
  spec.fov_deg = 180.0;
  spec.range_noise_std = 0.0;
  return spec;
}

}  // namespace uavslam::test
