#include "drivers/mavlink/AutopilotSession.hpp"

#include <algorithm>
#include <cmath>

#include "drivers/mavlink/CommonMessages.hpp"
#include "drivers/mavlink/FrameConventions.hpp"

namespace uavslam::mavlink {
namespace {

constexpr std::size_t kPendingRequests = 8;
constexpr std::uint8_t kDefaultSystemId = 1;  // until the autopilot's heartbeat tells its own

std::int64_t nanoseconds(double seconds) {
  return std::llround(seconds * 1e9);
}

std::vector<StreamRequest> wanted_streams(const SessionOptions& options) {
  return {{static_cast<std::uint16_t>(kAttitudeQuaternion), options.attitude_rate},
          {static_cast<std::uint16_t>(kHighresImu), options.imu_rate},
          {static_cast<std::uint16_t>(kLocalPositionNed),
           options.velocity_sigma > 0.0 ? options.velocity_rate : 0.0}};
}

}  // namespace

AutopilotSession::AutopilotSession(const SessionOptions& options)
    : options_(options),
      writer_(kDefaultSystemId, options.component_id),
      interval_requests_(wanted_streams(options), options.command_timeout,
                         options.command_attempts) {}

void AutopilotSession::receive(const std::uint8_t* data, std::size_t size, double host_now,
                               const OnImu& on_imu, const Send& send,
                               const OnVelocity& on_velocity) {
  reader_.feed(data, size,
               [&](const Frame& frame) { handle(frame, host_now, on_imu, send, on_velocity); });
}

void AutopilotSession::handle(const Frame& frame, double host_now, const OnImu& on_imu,
                              const Send& send, const OnVelocity& on_velocity) {
  switch (frame.message_id) {
    case kHeartbeat:
      handle_heartbeat(frame, host_now);
      return;
    case kSystemTime:
      clock_.add_one_way(
          static_cast<std::int64_t>(decode_system_time(frame.payload).time_boot_ms) * 1'000'000,
          host_now);
      return;
    case kTimesync:
      handle_timesync(frame, host_now, send);
      return;
    case kCommandAck:
      handle_command_ack(frame, host_now);
      return;
    case kCommandLong:
      handle_command_long(frame, send);
      return;
    case kHighresImu: {
      const HighresImu imu = decode_highres_imu(frame.payload);
      acceleration_frd_ = Eigen::Vector3d(imu.xacc, imu.yacc, imu.zacc);
      return;
    }
    case kAttitudeQuaternion: {
      const AttitudeQuaternion a = decode_attitude_quaternion(frame.payload);
      quaternions_seen_ = true;
      publish_attitude(a.time_boot_ms, Eigen::Quaterniond(a.q1, a.q2, a.q3, a.q4),
                       Eigen::Vector3d(a.rollspeed, a.pitchspeed, a.yawspeed), host_now, on_imu);
      return;
    }
    case kLocalPositionNed:
      publish_velocity(decode_local_position_ned(frame.payload), host_now, on_velocity);
      return;
    case kAttitude: {
      if (quaternions_seen_) return;
      const Attitude a = decode_attitude(frame.payload);
      publish_attitude(a.time_boot_ms, from_euler_zyx({a.roll, a.pitch, a.yaw}),
                       Eigen::Vector3d(a.rollspeed, a.pitchspeed, a.yawspeed), host_now, on_imu);
      return;
    }
    default:
      return;  // our own kind of messages echoed back, or ones we only send
  }
}

void AutopilotSession::handle_heartbeat(const Frame& frame, double host_now) {
  const Heartbeat heartbeat = decode_heartbeat(frame.payload);
  // Ours echoed back, a ground station's, a camera's: not a flight controller.
  if (heartbeat.type == kMavTypeOnboardController || heartbeat.autopilot == kMavAutopilotInvalid) {
    return;
  }
  ++counts_.heartbeats;
  const bool first = !autopilot_system_;
  const bool rebooted = !first && (frame.system_id != *autopilot_system_ ||
                                   host_now - last_heartbeat_ > options_.heartbeat_timeout);
  last_heartbeat_ = host_now;
  if (!first && !rebooted) return;
  if (rebooted) ++counts_.reboots;
  writer_.set_system_id(frame.system_id);  // a companion computer takes its vehicle's id
  autopilot_system_ = frame.system_id;
  autopilot_component_ = frame.component_id;
  interval_requests_.start(frame.system_id, frame.component_id);
}

void AutopilotSession::handle_command_ack(const Frame& frame, double host_now) {
  if (!autopilot_system_ || frame.system_id != *autopilot_system_ ||
      frame.component_id != autopilot_component_) {
    return;
  }
  const CommandAck ack = decode_command_ack(frame.payload);
  // Senders older than the target fields leave them 0; otherwise the answer must be ours.
  if (ack.target_system != 0 &&
      (ack.target_system != *autopilot_system_ || ack.target_component != options_.component_id)) {
    return;
  }
  interval_requests_.acknowledge(ack, host_now);
  counts_.interval_requests = interval_requests_.counts();
}

// The command protocol wants an answer to every command addressed to us; we carry out none.
void AutopilotSession::handle_command_long(const Frame& frame, const Send& send) {
  const CommandLong command = decode_command_long(frame.payload);
  if (!autopilot_system_ || command.target_system != *autopilot_system_ ||
      command.target_component != options_.component_id) {
    return;
  }
  CommandAck ack;
  ack.command = command.command;
  ack.result = kMavResultUnsupported;
  ack.target_system = frame.system_id;
  ack.target_component = frame.component_id;
  send(writer_.frame(kCommandAck, encode(ack)));
}

void AutopilotSession::handle_timesync(const Frame& frame, double host_now, const Send& send) {
  const Timesync sync = decode_timesync(frame.payload);
  if (sync.tc1 == 0) {  // the autopilot asks for our time
    send(writer_.frame(kTimesync, encode(Timesync{nanoseconds(host_now), sync.ts1, frame.system_id,
                                                  frame.component_id})));
    return;
  }
  const auto ours = std::find(pending_requests_.begin(), pending_requests_.end(), sync.ts1);
  if (ours == pending_requests_.end()) return;  // an answer to someone else
  pending_requests_.erase(ours);
  clock_.add_round_trip(static_cast<double>(sync.ts1) * 1e-9, sync.tc1, host_now);
  ++counts_.timesync_answers;
}

void AutopilotSession::publish_attitude(std::uint32_t time_boot_ms,
                                        const Eigen::Quaterniond& ned_frd,
                                        const Eigen::Vector3d& rates_frd, double host_now,
                                        const OnImu& on_imu) {
  if (!std::isfinite(ned_frd.norm()) || ned_frd.norm() < 0.5) return;  // not an attitude
  ImuSample sample;
  sample.stamp =
      clock_.host_time(static_cast<std::int64_t>(time_boot_ms) * 1'000'000).value_or(host_now);
  sample.orientation = enu_flu_from_ned_frd(ned_frd.normalized());
  sample.angular_velocity = flu_from_frd(rates_frd);
  sample.linear_acceleration = flu_from_frd(acceleration_frd_);
  ++counts_.imu_samples;
  on_imu(sample);
}

void AutopilotSession::publish_velocity(const LocalPositionNed& local, double host_now,
                                        const OnVelocity& on_velocity) {
  if (options_.velocity_sigma <= 0.0 || !on_velocity) return;
  const Eigen::Vector3d ned(local.vx, local.vy, local.vz);
  if (!ned.allFinite()) return;
  VelocitySample sample;
  sample.stamp = clock_.host_time(static_cast<std::int64_t>(local.time_boot_ms) * 1'000'000)
                     .value_or(host_now);
  sample.velocity = enu_from_ned(ned);
  sample.covariance =
      options_.velocity_sigma * options_.velocity_sigma * Eigen::Matrix3d::Identity();
  ++counts_.velocity_samples;
  on_velocity(sample);
}

void AutopilotSession::tick(double host_now, const Send& send) {
  if (host_now >= next_heartbeat_) {
    Heartbeat heartbeat;
    heartbeat.type = kMavTypeOnboardController;
    heartbeat.autopilot = kMavAutopilotInvalid;
    heartbeat.system_status = kMavStateActive;
    send(writer_.frame(kHeartbeat, encode(heartbeat)));
    next_heartbeat_ = host_now + options_.heartbeat_period;
  }
  if (host_now >= next_timesync_ && autopilot_system_) {
    const std::int64_t now = nanoseconds(host_now);
    pending_requests_.push_back(now);
    if (pending_requests_.size() > kPendingRequests) pending_requests_.pop_front();
    send(writer_.frame(kTimesync,
                       encode(Timesync{0, now, *autopilot_system_, autopilot_component_})));
    next_timesync_ = host_now + options_.timesync_period;
  }
  interval_requests_.tick(host_now, [&](const CommandLong& command) {
    send(writer_.frame(kCommandLong, encode(command)));
  });
  counts_.interval_requests = interval_requests_.counts();
}

void AutopilotSession::send_pose(const PoseEstimate& estimate, const Send& send) {
  // A pose no scan confirmed was carried by the IMU's motion: the autopilot's own estimator has
  // that IMU, and would count it twice.
  if (!(estimate.quality > 0.0f)) {
    ++counts_.poses_withheld;
    return;
  }
  const std::uint8_t reset = reset_counter_.update(estimate);
  if (options_.pose_message == PoseMessage::kOdometry) {
    send(writer_.frame(kOdometry, encode(odometry(estimate, reset))));
  } else {
    send(writer_.frame(kVisionPositionEstimate, encode(vision_position_estimate(estimate, reset))));
  }
  ++counts_.poses_sent;
}

}  // namespace uavslam::mavlink
