// The data the SLAM core works on: points, poses, IMU samples and laser scans.
// Plain values only: the core knows nothing of DDS, files or clocks; stamps are seconds.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace uavslam {

using Vec3 = Eigen::Vector3d;
using Points = std::vector<Vec3>;

// A rigid pose of the UAV body in the world frame at a time.
struct Pose {
  double stamp = 0.0;
  Vec3 position = Vec3::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();

  Eigen::Isometry3d isometry() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = orientation.toRotationMatrix();
    T.translation() = position;
    return T;
  }
};

// One sample of the orientation source (IMU / autopilot attitude), body frame to world frame.
struct ImuSample {
  double stamp = 0.0;
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Vec3 angular_velocity = Vec3::Zero();     // rad/s, body frame
  Vec3 linear_acceleration = Vec3::Zero();  // m/s^2, body frame, gravity included (specific force)
};

// One position of a second motion source (wheel odometry), the motion prior's input.
struct OdometrySample {
  double stamp = 0.0;            // s
  Vec3 position = Vec3::Zero();  // m, in the odometry's own frame
};

// One velocity of a third motion source: the autopilot's own estimate (from optical flow or
// visual-inertial odometry; MAVLink LOCAL_POSITION_NED, ODOMETRY), in the orientation source's
// frame, with the covariance the source states.
struct VelocitySample {
  double stamp = 0.0;                                    // s
  Vec3 velocity = Vec3::Zero();                          // m/s
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // (m/s)^2
};

// The fixed geometry of a range sensor: where each beam points, which ranges are valid and where
// the sensor sits on the body. A planar scanner, one with beams deflected by a mirror and a
// multi-ring scanner all reduce to a list of beam directions.
struct ScanGeometry {
  std::vector<Vec3> directions;  // unit vectors in the sensor frame, one per beam
  double min_range = 0.1;        // m; shorter returns are invalid
  double max_range = 30.0;       // m; longer returns are invalid
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  // sensor frame -> body frame
  // s after the scan's stamp that each beam fires, one per beam: a scanning LiDAR sweeps its beams
  // in turn (a UTM-30LX's 270 degrees take 18.75 ms). Empty: every beam at the stamp.
  std::vector<double> fire_times;

  // A planar scanner in the sensor's x-y plane: beam i at angle_min + i * angle_increment
  // (the sensor_msgs/LaserScan convention).
  static ScanGeometry planar(double angle_min, double angle_increment, int beams);

  // Beam i fires time_increment * i after the stamp (sensor_msgs/LaserScan's time_increment);
  // 0 clears the fire times.
  void sweep_beams_in_order(double time_increment);
  // s from the first beam fired to the last; 0 without fire times.
  double sweep_seconds() const;

  // Some beams point more up or down than sideways on the body (is_vertical: a floor mirror, the
  // rings of a 3D scanner): the sensor can measure height. A planar scanner's cannot.
  bool has_vertical_beams() const;
};

// A direction more up or down than sideways (over 45 degrees from the horizontal).
inline bool is_vertical(const Vec3& direction) {
  return std::abs(direction.z()) > std::sqrt(0.5);
}

// One sweep of the range sensor: a range per beam of its geometry (NaN/inf/out of range = no
// return).
struct Scan {
  double stamp = 0.0;
  std::uint64_t sequence = 0;
  std::shared_ptr<const ScanGeometry> geometry;
  std::vector<float> ranges;
  std::vector<float> intensities;  // empty when the sensor gives none
};

}  // namespace uavslam
