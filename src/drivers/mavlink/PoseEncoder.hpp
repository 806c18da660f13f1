// The matcher's pose (world ENU, body FLU, covariance over x, y, z, roll, pitch, yaw) as the
// external-vision messages the autopilots fuse: VISION_POSITION_ESTIMATE or ODOMETRY, in local NED
// with the FRD body (FrameConventions.hpp). Stamps are host time in us: PX4 maps them to its clock
// through the TIMESYNC offset it measures against our answers (which carry the same host clock);
// ArduPilot estimates the offset from the stamps' own stream.
#pragma once

#include <array>
#include <cstdint>

#include "core/Types.hpp"
#include "drivers/mavlink/Messages.hpp"

namespace uavslam::mavlink {

struct PoseEstimate {
  Pose pose;                            // stamp: host time, s
  std::array<double, 36> covariance{};  // row-major 6x6, ENU/FLU; all zero: unknown
  float quality = 1.0f;                 // 0 (lost) .. 1
  std::uint64_t scan_seq = 0;
};

// The reset counter the autopilot uses to discard its EV state when our estimate jumps. Rule: it
// steps (wrapping at 255) when the matcher restarted (scan_seq went backwards: a new map, a new
// origin) or when the position moved further between two poses than the vehicle can fly
// (jump_distance + max_speed * dt: a relocalisation or a map correction).
class ResetCounter {
 public:
  ResetCounter(double jump_distance = 0.5, double max_speed = 5.0)
      : jump_distance_(jump_distance), max_speed_(max_speed) {}
  std::uint8_t update(const PoseEstimate& estimate);
  std::uint8_t value() const { return value_; }

 private:
  double jump_distance_;
  double max_speed_;
  bool has_previous_ = false;
  PoseEstimate previous_;
  std::uint8_t value_ = 0;
};

VisionPositionEstimate vision_position_estimate(const PoseEstimate& estimate,
                                                std::uint8_t reset_counter);
// Pose only: velocities NaN (unknown) and velocity_covariance[0] NaN, as common.xml asks.
Odometry odometry(const PoseEstimate& estimate, std::uint8_t reset_counter);

// The 21 upper-triangle entries (row-major) of the pose covariance in NED/FRD; [0] NaN when the
// covariance is unknown (all zero).
std::array<float, 21> ned_upper_triangle(const std::array<double, 36>& enu_flu);

}  // namespace uavslam::mavlink
