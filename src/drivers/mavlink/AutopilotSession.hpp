// The companion computer's side of a MAVLink link to an autopilot, independent of the transport
// (bytes in, bytes out, host time given): it reads the autopilot's attitude and IMU messages into
// our ImuSample (ENU/FLU, host-time stamps through AutopilotClock), announces itself with a
// HEARTBEAT (MAV_TYPE_ONBOARD_CONTROLLER) once a second, measures the clock offset with TIMESYNC
// requests once a second and answers the autopilot's own TIMESYNC requests with host time, and
// encodes our poses as VISION_POSITION_ESTIMATE or ODOMETRY. Not thread-safe: one owner.
//
// Once the autopilot is heard (its first HEARTBEAT: a flight controller's, autopilot field not
// MAV_AUTOPILOT_INVALID), it asks for the streams it reads with MAV_CMD_SET_MESSAGE_INTERVAL
// (MessageIntervalRequests.hpp): ATTITUDE_QUATERNION and HIGHRES_IMU at the options' rates (0:
// not asked, the autopilot's own rate stays). Asked again when the autopilot reboots: its
// HEARTBEAT comes back after a silence longer than heartbeat_timeout, or from another system id.
//
// With options.velocity_sigma > 0, one velocity per LOCAL_POSITION_NED (asked for at
// velocity_rate), in ENU, stated to velocity_sigma (the message carries no accuracy): only for an
// autopilot whose velocity comes from its own aiding (optical flow, VIO), not from our poses.
//
// One `imu` sample per ATTITUDE_QUATERNION (or per ATTITUDE while no ATTITUDE_QUATERNION has
// arrived), with the attitude's rates and the newest HIGHRES_IMU's accelerations (zero before
// one arrived). Stamped by the attitude's time_boot_ms mapped to host time; before the clock is
// synchronised, by the arrival time.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/Types.hpp"
#include "drivers/mavlink/AutopilotClock.hpp"
#include "drivers/mavlink/FrameReader.hpp"
#include "drivers/mavlink/FrameWriter.hpp"
#include "drivers/mavlink/MessageIntervalRequests.hpp"
#include "drivers/mavlink/Messages.hpp"
#include "drivers/mavlink/PoseEncoder.hpp"

namespace uavslam::mavlink {

enum class PoseMessage { kVisionPositionEstimate, kOdometry };

struct SessionOptions {
  std::uint8_t component_id = kMavCompIdVisualInertialOdometry;
  PoseMessage pose_message = PoseMessage::kVisionPositionEstimate;
  double heartbeat_period = 1.0;   // s
  double timesync_period = 1.0;    // s
  double attitude_rate = 200.0;    // Hz of ATTITUDE_QUATERNION to ask for; 0: do not ask
  double imu_rate = 200.0;         // Hz of HIGHRES_IMU to ask for; 0: do not ask
  double velocity_sigma = 0.0;     // m/s stated for LOCAL_POSITION_NED's velocity; 0: not read
  double velocity_rate = 20.0;     // Hz of LOCAL_POSITION_NED to ask for (when read); 0: do not ask
  double command_timeout = 1.0;    // s to wait for a COMMAND_ACK before sending again
  int command_attempts = 3;        // transmissions of one request before giving up
  double heartbeat_timeout = 3.0;  // s of silence after which a HEARTBEAT means a reboot
};

struct SessionCounts {
  std::uint64_t heartbeats = 0;        // from the autopilot
  std::uint64_t imu_samples = 0;       // handed on
  std::uint64_t velocity_samples = 0;  // handed on
  std::uint64_t timesync_answers = 0;  // to our requests
  std::uint64_t poses_sent = 0;
  std::uint64_t poses_withheld = 0;  // quality 0: dead-reckoned, no scan confirmed them
  std::uint64_t reboots = 0;  // its HEARTBEAT back after a silence (or a lost link) or renumbered
  IntervalRequestCounts interval_requests;  // SET_MESSAGE_INTERVAL
};

class AutopilotSession {
 public:
  using Send = std::function<void(const std::vector<std::uint8_t>&)>;
  using OnImu = std::function<void(const ImuSample&)>;
  using OnVelocity = std::function<void(const VelocitySample&)>;

  explicit AutopilotSession(const SessionOptions& options = {});

  // Bytes from the autopilot, received at host_now (s): on_imu (on_velocity) for each sample
  // they complete, send for the answers they need.
  void receive(const std::uint8_t* data, std::size_t size, double host_now, const OnImu& on_imu,
               const Send& send, const OnVelocity& on_velocity = {});
  // The periodic HEARTBEAT and TIMESYNC request and the stream requests, when due.
  void tick(double host_now, const Send& send);
  // One pose to the autopilot, with the reset counter's rule (PoseEncoder.hpp).
  void send_pose(const PoseEstimate& estimate, const Send& send);

  bool autopilot_heard() const { return autopilot_system_.has_value(); }
  const FrameCounts& frame_counts() const { return reader_.counts(); }
  const SessionCounts& counts() const { return counts_; }
  const AutopilotClock& clock() const { return clock_; }
  // What became of the stream requests since the last call, a line each, for the operator.
  std::vector<std::string> take_reports() { return interval_requests_.take_reports(); }

 private:
  void handle(const Frame& frame, double host_now, const OnImu& on_imu, const Send& send,
              const OnVelocity& on_velocity);
  void publish_velocity(const LocalPositionNed& local, double host_now,
                        const OnVelocity& on_velocity);
  void handle_heartbeat(const Frame& frame, double host_now);
  void handle_timesync(const Frame& frame, double host_now, const Send& send);
  void handle_command_ack(const Frame& frame, double host_now);
  void handle_command_long(const Frame& frame, const Send& send);
  void publish_attitude(std::uint32_t time_boot_ms, const Eigen::Quaterniond& ned_frd,
                        const Eigen::Vector3d& rates_frd, double host_now, const OnImu& on_imu);

  SessionOptions options_;
  FrameReader reader_;
  FrameWriter writer_;
  AutopilotClock clock_;
  ResetCounter reset_counter_;
  SessionCounts counts_;
  std::optional<std::uint8_t> autopilot_system_;
  std::uint8_t autopilot_component_ = 1;
  double last_heartbeat_ = 0;  // host time
  MessageIntervalRequests interval_requests_;
  bool quaternions_seen_ = false;
  Eigen::Vector3d acceleration_frd_ = Eigen::Vector3d::Zero();
  std::deque<std::int64_t> pending_requests_;  // ts1 of our TIMESYNC requests, ns
  double next_heartbeat_ = 0;
  double next_timesync_ = 0;
};

}  // namespace uavslam::mavlink
