#include "drivers/mavlink/FrameConventions.hpp"

#include <algorithm>
#include <cmath>

namespace uavslam::mavlink {
namespace {

Eigen::Matrix3d enu_to_ned() {
  Eigen::Matrix3d m;
  m << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  return m;
}

Eigen::Matrix3d flu_to_frd() {
  return Eigen::Vector3d(1, -1, -1).asDiagonal();
}

}  // namespace

Eigen::Vector3d ned_from_enu(const Eigen::Vector3d& enu) {
  return enu_to_ned() * enu;
}
Eigen::Vector3d enu_from_ned(const Eigen::Vector3d& ned) {
  return enu_to_ned() * ned;
}
Eigen::Vector3d frd_from_flu(const Eigen::Vector3d& flu) {
  return flu_to_frd() * flu;
}
Eigen::Vector3d flu_from_frd(const Eigen::Vector3d& frd) {
  return flu_to_frd() * frd;
}

Eigen::Quaterniond ned_frd_from_enu_flu(const Eigen::Quaterniond& enu_flu) {
  const Eigen::Matrix3d r = enu_to_ned() * enu_flu.toRotationMatrix() * flu_to_frd();
  return Eigen::Quaterniond(r).normalized();
}

Eigen::Quaterniond enu_flu_from_ned_frd(const Eigen::Quaterniond& ned_frd) {
  const Eigen::Matrix3d r = enu_to_ned() * ned_frd.toRotationMatrix() * flu_to_frd();
  return Eigen::Quaterniond(r).normalized();
}

EulerAngles euler_zyx(const Eigen::Quaterniond& rotation) {
  const Eigen::Matrix3d r = rotation.normalized().toRotationMatrix();
  EulerAngles angles;
  angles.pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  angles.roll = std::atan2(r(2, 1), r(2, 2));
  angles.yaw = std::atan2(r(1, 0), r(0, 0));
  return angles;
}

Eigen::Quaterniond from_euler_zyx(const EulerAngles& angles) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angles.yaw, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(angles.pitch, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(angles.roll, Eigen::Vector3d::UnitX()));
}

Matrix6d ned_frd_covariance(const Matrix6d& enu_flu) {
  Matrix6d jacobian = Matrix6d::Zero();
  jacobian.topLeftCorner<3, 3>() = enu_to_ned();
  jacobian.bottomRightCorner<3, 3>() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  return jacobian * enu_flu * jacobian.transpose();
}

}  // namespace uavslam::mavlink
