// The motion prior's answer for one scan: where another source (wheel odometry, the IMU's
// accelerations) says the body went since the previous posed scan, and how sure it is. The seed has
// no motion model: no motion, unknown.
#pragma once

#include <optional>

#include "core/Types.hpp"

namespace uavslam {

struct MotionPrediction {
  Vec3 motion = Vec3::Zero();  // m, in the frame of the orientation source
  // m^2; the motion's uncertainty, and the pose's since the previous posed scan. None: the source
  // gives no uncertainty (a directions the scan cannot see then keeps the motion as it is).
  std::optional<Eigen::Matrix3d> covariance;
};

}  // namespace uavslam
