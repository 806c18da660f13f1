// A simulated flight: the world, the trajectory through it and the sensors flown (the LiDAR
// described as a real one is, sensor/LidarSpec.hpp).
// One scenario is one YAML file in config/scenarios (read by io/ScenarioFile).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/Types.hpp"
#include "sensor/LidarSpec.hpp"

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

// A vertical wall bent round a circle (a round hall's wall, with a gap for its door): the circle
// of `radius` about `center` from from_deg to to_deg (counter-clockwise from +x), z0 to z1 high.
// A surface of no thickness, seen from either side.
struct ArcWall {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
  double from_deg = 0.0, to_deg = 360.0;
  double z0 = 0.0, z1 = 0.0;
};

// A person walking through the world: a vertical cylinder going to and fro along a path at a
// steady pace (sim/Walker: where it is when). Scans see it; the map should not keep it.
struct Walker {
  std::vector<Eigen::Vector2d> path;  // at least two points; walked to the end and back
  double speed = 1.2;                 // m/s
  double start = 0.0;                 // m along the path at t = 0
  double radius = 0.25;               // m
  double height = 1.8;                // m, from the floor (z = 0)
};

struct WorldSpec {
  Box room;  // the inside of floor, ceiling and four walls
  std::vector<Box> boxes;
  std::vector<Cylinder> cylinders;
  std::vector<ArcWall> arcs;
  std::vector<Walker> people;  // what moves: seen by the scans, not part of the map's truth
};

// What flies the trajectory: a multirotor tilts along its acceleration; a ground robot stays level.
enum class Vehicle { multirotor, ground };

struct Waypoint {
  double t = 0.0;  // s
  Vec3 position = Vec3::Zero();
  double yaw_deg = 0.0;
};

// From `t` s into the flight on, the heading drifts at this rate instead (a gyro's bias moves
// with its temperature).
struct DriftChange {
  double t = 0.0;
  double deg_per_min = 0.0;
};

struct ImuSpec {
  double rate_hz = 200.0;
  double orientation_noise_std_deg = 0.1;
  double yaw_drift_deg_per_min = 0.0;
  std::vector<DriftChange> yaw_drift_changes;  // in time order
  double gyro_noise_std = 0.001;               // rad/s
  double accel_noise_std = 0.02;               // m/s^2
  // m/s^2 per body axis, constant: what the accelerometer adds to the specific force (a real
  // one's calibration leaves a few hundredths; zero, the ideal sensor, unless a scenario says).
  Vec3 accel_bias = Vec3::Zero();
};

// The autopilot's velocity estimate (from optical flow or visual-inertial odometry), reported in
// the same drifting heading frame as the IMU's attitude.
struct VelocitySpec {
  double rate_hz = 0.0;     // samples per second; 0: the vehicle has no such source
  double noise_std = 0.05;  // m/s per axis, white, as the samples' covariance states it
};

// Sensor faults to fly through (none unless a scenario says).
struct FaultSpec {
  // Every late_scan_every-th scan was taken late_scan_s before its stamp: a latency spike on the
  // scanner's link (USB, serial) that the stamp does not show. 0: none.
  int late_scan_every = 0;
  double late_scan_s = 0.0;
};

// A ground robot's wheel odometry, for a flight written as a CARMEN log (uavslam simulate
// --carmen): the true motion between scans in the body frame, off by a scale and by noise that
// grows as a random walk with the motion (so it does not depend on how often it is sampled),
// integrated from the first pose.
struct WheelOdometrySpec {
  double translation_scale_error = 0.01;  // the wheels' radius off by this fraction
  double turn_scale_error = 0.02;         // the wheel base off by this fraction
  double translation_noise = 0.01;        // m per sqrt(m) travelled
  double turn_noise = 0.01;               // rad per sqrt(rad) turned
  double turn_per_metre_noise = 0.005;    // rad per sqrt(m) travelled (slip on a straight line)
};

struct Scenario {
  std::string name;
  WorldSpec world;
  std::vector<Waypoint> waypoints;
  Vehicle vehicle = Vehicle::multirotor;
  LidarSpec lidar;
  ImuSpec imu;
  VelocitySpec velocity;
  FaultSpec faults;
  WheelOdometrySpec odometry;
  std::uint64_t seed = 1;
};

}  // namespace uavslam::sim
