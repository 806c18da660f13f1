// Our frames against the autopilots'. uavslam (src/sim, src/core/Types.hpp): world z up with x, y
// horizontal, treated as ENU (x east, y north), body FLU (x forward, y left, z up); an
// orientation turns body vectors into world vectors; at rest the accelerometer reads +g on body z.
// PX4 and ArduPilot (MAVLink common.xml): world NED (x north, y east, z down), body FRD (x forward,
// y right, z down); at rest the accelerometer reads -g on body z.
//   world: ned = M enu, M = [[0,1,0],[1,0,0],[0,0,-1]] (= Rz(90 deg) Rx(180 deg), its own inverse)
//   body:  frd = F flu, F = diag(1,-1,-1) (= Rx(180 deg), its own inverse)
//   orientation: R_ned_frd = M R_enu_flu F
//   ZYX Euler angles: roll_frd = roll_flu, pitch_frd = -pitch_flu, yaw_ned = 90 deg - yaw_enu
//   (a yaw of 0 in ENU faces east, which is yaw 90 deg in NED; ENU +90 deg faces north, NED 0).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace uavslam::mavlink {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct EulerAngles {
  double roll = 0, pitch = 0, yaw = 0;  // rad; R = Rz(yaw) Ry(pitch) Rx(roll)
};

Eigen::Vector3d ned_from_enu(const Eigen::Vector3d& enu);
Eigen::Vector3d enu_from_ned(const Eigen::Vector3d& ned);
Eigen::Vector3d frd_from_flu(const Eigen::Vector3d& flu);
Eigen::Vector3d flu_from_frd(const Eigen::Vector3d& frd);

Eigen::Quaterniond ned_frd_from_enu_flu(const Eigen::Quaterniond& enu_flu);
Eigen::Quaterniond enu_flu_from_ned_frd(const Eigen::Quaterniond& ned_frd);

// ZYX (yaw, pitch, roll) angles of a rotation and back; pitch in [-90, 90] deg.
EulerAngles euler_zyx(const Eigen::Quaterniond& rotation);
Eigen::Quaterniond from_euler_zyx(const EulerAngles& angles);

// A pose covariance over (x, y, z, roll, pitch, yaw) in ENU/FLU, as the `pose` topic carries it,
// in NED/FRD: C' = J C J^T with J = blockdiag(M, diag(1, -1, -1)), the Jacobian of the maps above.
Matrix6d ned_frd_covariance(const Matrix6d& enu_flu);

}  // namespace uavslam::mavlink
