// The motion prior's answer for one scan: where another source (wheel odometry, the IMU's
// accelerations) says the body went since the previous posed scan, and how sure it is. The seed has
// no motion model: no motion, unknown.
#pragma once

#include <optional>

#include "core/Types.hpp"

namespace uavslam {

struct MotionPrediction {
  Vec3 motion = Vec3::Zero();  // m, in the frame of the orientation source
  // m^2; the covariance of the predicted position (the last pose moved by the motion). None: the
  // source gives no uncertainty (the pipeline then grows the last pose's by recovery.max_speed).
  std::optional<Eigen::Matrix3d> covariance;
};

}  // namespace uavslam
