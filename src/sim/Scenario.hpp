// A simulated flight: the world, the trajectory through it and the sensors flown.
// One scenario is one YAML file in config/scenarios (read by io/ScenarioFile).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/Types.hpp"

namespace uavslam::sim {

struct Box {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
};

struct Cylinder {  // vertical
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
  double z0 = 0.0, z1 = 0.0;
};

struct WorldSpec {
  Box room;  // the inside of floor, ceiling and four walls
  std::vector<Box> boxes;
  std::vector<Cylinder> cylinders;
};

struct Waypoint {
  double t = 0.0;  // s
  Vec3 position = Vec3::Zero();
  double yaw_deg = 0.0;
};

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
  Vec3 mount_position{0.0, 0.0, 0.1};
  Vec3 mount_rpy_deg = Vec3::Zero();
  FloorMirrorSpec floor_mirror;
  int rings = 1;                   // > 1: a multi-ring 3D scanner
  double vertical_fov_deg = 30.0;  // total, symmetric about the horizontal, used when rings > 1
};

struct ImuSpec {
  double rate_hz = 200.0;
  double orientation_noise_std_deg = 0.1;
  double yaw_drift_deg_per_min = 0.0;
  double gyro_noise_std = 0.001;  // rad/s
  double accel_noise_std = 0.02;  // m/s^2
};

struct Scenario {
  std::string name;
  WorldSpec world;
  std::vector<Waypoint> waypoints;
  LidarSpec lidar;
  ImuSpec imu;
  std::uint64_t seed = 1;
};

}  // namespace uavslam::sim
