#include "drivers/mavlink/PoseEncoder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "drivers/mavlink/FrameConventions.hpp"

namespace uavslam::mavlink {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

std::uint64_t host_usec(double stamp) {
  return stamp > 0 ? static_cast<std::uint64_t>(std::llround(stamp * 1e6)) : 0;
}

// common.xml's ODOMETRY quality: -1 failed, 0 unknown, 1 worst .. 100 best.
std::int8_t odometry_quality(float quality) {
  if (!(quality > 0.0f)) return -1;
  return static_cast<std::int8_t>(std::clamp(std::lround(quality * 100.0f), 1L, 100L));
}

}  // namespace

std::uint8_t ResetCounter::update(const PoseEstimate& estimate) {
  if (has_previous_) {
    const double dt = std::abs(estimate.pose.stamp - previous_.pose.stamp);
    const double moved = (estimate.pose.position - previous_.pose.position).norm();
    const bool restarted = estimate.scan_seq < previous_.scan_seq;
    if (restarted || moved > jump_distance_ + max_speed_ * dt) ++value_;
  }
  previous_ = estimate;
  has_previous_ = true;
  return value_;
}

std::array<float, 21> ned_upper_triangle(const std::array<double, 36>& enu_flu) {
  std::array<float, 21> out{};
  if (std::all_of(enu_flu.begin(), enu_flu.end(), [](double v) { return v == 0.0; })) {
    out[0] = kNaN;
    return out;
  }
  const Matrix6d ned = ned_frd_covariance(
      Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(enu_flu.data()));
  std::size_t k = 0;
  for (int row = 0; row < 6; ++row) {
    for (int col = row; col < 6; ++col) out[k++] = static_cast<float>(ned(row, col));
  }
  return out;
}

VisionPositionEstimate vision_position_estimate(const PoseEstimate& estimate,
                                                std::uint8_t reset_counter) {
  const Eigen::Vector3d position = ned_from_enu(estimate.pose.position);
  const EulerAngles angles = euler_zyx(ned_frd_from_enu_flu(estimate.pose.orientation));
  VisionPositionEstimate m;
  m.usec = host_usec(estimate.pose.stamp);
  m.x = static_cast<float>(position.x());
  m.y = static_cast<float>(position.y());
  m.z = static_cast<float>(position.z());
  m.roll = static_cast<float>(angles.roll);
  m.pitch = static_cast<float>(angles.pitch);
  m.yaw = static_cast<float>(angles.yaw);
  m.covariance = ned_upper_triangle(estimate.covariance);
  m.reset_counter = reset_counter;
  return m;
}

Odometry odometry(const PoseEstimate& estimate, std::uint8_t reset_counter) {
  const Eigen::Vector3d position = ned_from_enu(estimate.pose.position);
  const Eigen::Quaterniond q = ned_frd_from_enu_flu(estimate.pose.orientation);
  Odometry m;
  m.time_usec = host_usec(estimate.pose.stamp);
  m.frame_id = kMavFrameLocalNed;
  m.child_frame_id = kMavFrameBodyFrd;
  m.x = static_cast<float>(position.x());
  m.y = static_cast<float>(position.y());
  m.z = static_cast<float>(position.z());
  m.q = {static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()),
         static_cast<float>(q.z())};
  m.vx = m.vy = m.vz = kNaN;
  m.rollspeed = m.pitchspeed = m.yawspeed = kNaN;
  m.pose_covariance = ned_upper_triangle(estimate.covariance);
  m.velocity_covariance[0] = kNaN;
  m.reset_counter = reset_counter;
  m.estimator_type = kMavEstimatorTypeLidar;
  m.quality = odometry_quality(estimate.quality);
  return m;
}

}  // namespace uavslam::mavlink
