// Trajectories with a known shape for the eval tests: a climbing, turning flight whose positions
// are not collinear, so an SE3 alignment of it is fully determined.
#pragma once

#include <cmath>
#include <vector>

#include "core/Types.hpp"

namespace uavslam::eval::test {

// `count` poses at `rate_hz` from t = 100 s: a 2 m circle at 0.3 rad/s, bobbing 0.2 m in z,
// nose along the direction of flight and a small roll.
inline std::vector<Pose> circling_flight(int count = 200, double rate_hz = 10.0) {
  std::vector<Pose> poses;
  for (int k = 0; k < count; ++k) {
    const double t = k / rate_hz;
    Pose pose;
    pose.stamp = 100.0 + t;
    pose.position =
        Vec3(2.0 * std::cos(0.3 * t), 2.0 * std::sin(0.3 * t), 1.0 + 0.2 * std::sin(0.5 * t));
    pose.orientation = Eigen::AngleAxisd(0.3 * t + EIGEN_PI / 2, Vec3::UnitZ()) *
                       Eigen::AngleAxisd(0.05 * std::sin(t), Vec3::UnitX());
    poses.push_back(pose);
  }
  return poses;
}

// The poses moved rigidly: each becomes motion * pose.
inline std::vector<Pose> moved(std::vector<Pose> poses, const Eigen::Isometry3d& motion) {
  const Eigen::Quaterniond rotation(motion.linear());
  for (Pose& pose : poses) {
    pose.position = motion * pose.position;
    pose.orientation = rotation * pose.orientation;
  }
  return poses;
}

// The poses with every position shifted by the same world-frame offset.
inline std::vector<Pose> offset(std::vector<Pose> poses, const Vec3& shift) {
  for (Pose& pose : poses) pose.position += shift;
  return poses;
}

}  // namespace uavslam::eval::test
