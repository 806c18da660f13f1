// Angle conversions: degrees and radians, wrapping, roll-pitch-yaw in degrees (sensor mounts,
// scenarios).
#pragma once

#include <cmath>

#include "core/Types.hpp"

namespace uavslam {

constexpr double kPi = 3.14159265358979323846;

constexpr double deg_to_rad(double degrees) {
  return degrees * kPi / 180.0;
}
constexpr double rad_to_deg(double radians) {
  return radians * 180.0 / kPi;
}
// A turn rate in rad/s as degrees a minute (how a heading drift is stated).
constexpr double degrees_per_minute(double radians_per_second) {
  return rad_to_deg(radians_per_second) * 60.0;
}

// The angle in (-pi, pi] equivalent to `radians`.
inline double wrap_angle(double radians) {
  return std::remainder(radians, 2.0 * kPi);
}

// Roll about x, then pitch about y, then yaw about z: R = Rz * Ry * Rx.
inline Eigen::Quaterniond rotation_from_rpy_deg(const Vec3& rpy_deg) {
  return Eigen::AngleAxisd(deg_to_rad(rpy_deg.z()), Vec3::UnitZ()) *
         Eigen::AngleAxisd(deg_to_rad(rpy_deg.y()), Vec3::UnitY()) *
         Eigen::AngleAxisd(deg_to_rad(rpy_deg.x()), Vec3::UnitX());
}

}  // namespace uavslam
