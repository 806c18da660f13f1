// What a LiDAR is, as a sensor file (config/sensors/*.yaml) or a scenario's `lidar` section
// describes it: beam layout, range limits, where it sits on the body and the floor mirror. The
// matcher on a real vehicle and the simulator read the same description; only range_noise_std
// is the simulator's alone.
#pragma once

#include <string>

#include "core/Types.hpp"

namespace uavslam {

// Height from a planar scanner: a few beams at one edge of the field of view hit a 45-degree
// mirror and fan out towards the floor (as on many indoor UAVs with a Hokuyo).
struct FloorMirrorSpec {
  int beams = 0;             // beams taken from the start of the scan (0 = no mirror)
  double spread_deg = 20.0;  // the fan's total opening across the floor
};

struct LidarSpec {
  int beams = 1080;
  double fov_deg = 270.0;
  double rate_hz = 40.0;
  double min_range = 0.1;
  double max_range = 30.0;
  double range_noise_std = 0.01;  // m, Gaussian
  // s from the first beam to the last (a UTM-30LX's 270 of 360 degrees at 40 Hz: 18.75 ms); a
  // vehicle that moves or turns meanwhile sees each beam from where it was then. 0: every beam at
  // the scan's stamp (the default; the shipped scenarios and sensor file give the UTM-30LX's).
  double sweep_seconds = 0.0;
  Vec3 mount_position{0.0, 0.0, 0.1};
  Vec3 mount_rpy_deg = Vec3::Zero();
  FloorMirrorSpec floor_mirror;
  int rings = 1;                   // > 1: a multi-ring 3D scanner
  double vertical_fov_deg = 30.0;  // total, symmetric about the horizontal, used when rings > 1
};

// A named sensor: what `slam_matcher --sensor FILE` reads (io::load_sensor).
struct SensorDescription {
  std::string name;
  LidarSpec lidar;
};

}  // namespace uavslam
