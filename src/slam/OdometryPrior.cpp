#include "slam/OdometryPrior.hpp"

namespace uavslam {

OdometryPrior::OdometryPrior(double max_gap, const SlamConfig::Motion& noise, std::size_t capacity)
    : buffer_(max_gap, capacity), noise_(noise) {}

MotionPrediction OdometryPrior::motion_to(double t) {
  const std::optional<Vec3> now = buffer_.position_at(t);
  if (!now || !last_posed_) {
    ++without_prior_;
    return {};
  }
  ++with_prior_;
  MotionPrediction prediction;
  prediction.motion = *now - *last_posed_;
  const double sigma =
      noise_.odometry_noise_floor + noise_.odometry_noise_per_metre * prediction.motion.norm();
  prediction.covariance = posed_covariance_ + sigma * sigma * Eigen::Matrix3d::Identity();
  return prediction;
}

void OdometryPrior::scan_posed(double t, const Eigen::Matrix3d& covariance) {
  last_posed_ = buffer_.position_at(t);
  posed_covariance_ = covariance;
}

}  // namespace uavslam
