// The fields of the common.xml messages this driver uses, and their payload codecs (field
// offsets from CommonMessages.hpp). Units and frames as common.xml gives them: angles in rad,
// NED world / FRD body, times in the autopilot's clock (time since its boot, or Unix time).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace uavslam::mavlink {

// MAV_TYPE, MAV_AUTOPILOT, MAV_STATE, MAV_COMPONENT, MAV_FRAME, MAV_ESTIMATOR_TYPE values used
// here (common.xml enums).
inline constexpr std::uint8_t kMavTypeOnboardController = 18;
inline constexpr std::uint8_t kMavAutopilotInvalid = 8;
inline constexpr std::uint8_t kMavStateActive = 4;
inline constexpr std::uint8_t kMavCompIdVisualInertialOdometry = 197;
inline constexpr std::uint8_t kMavFrameLocalNed = 1;
inline constexpr std::uint8_t kMavFrameBodyFrd = 12;
inline constexpr std::uint8_t kMavEstimatorTypeLidar = 7;
inline constexpr std::uint8_t kMavlinkVersion = 3;  // common.xml's <version>

// MAV_CMD_SET_MESSAGE_INTERVAL (common.xml MAV_CMD 511): param1 the message id, param2 the
// interval in us (-1: stop the message, 0: its default rate), on the link the command came in on.
inline constexpr std::uint16_t kMavCmdSetMessageInterval = 511;

// MAV_RESULT: a COMMAND_ACK's result.
enum MavResult : std::uint8_t {
  kMavResultAccepted = 0,
  kMavResultTemporarilyRejected = 1,  // valid, cannot run now: retrying later should work
  kMavResultDenied = 2,               // supported, invalid parameters: retrying will not work
  kMavResultUnsupported = 3,          // unknown command
  kMavResultFailed = 4,               // valid, failed
  kMavResultInProgress = 5,           // more ACKs follow, the last with the final result
  kMavResultCancelled = 6,
};
// "MAV_RESULT_DENIED", ...; "MAV_RESULT <n>" for a value common.xml may have added since.
std::string mav_result_name(std::uint8_t result);

struct Heartbeat {
  std::uint8_t type = 0;
  std::uint8_t autopilot = 0;
  std::uint8_t base_mode = 0;
  std::uint32_t custom_mode = 0;
  std::uint8_t system_status = 0;
  std::uint8_t mavlink_version = kMavlinkVersion;
};

struct SystemTime {
  std::uint64_t time_unix_usec = 0;
  std::uint32_t time_boot_ms = 0;
};

struct Attitude {
  std::uint32_t time_boot_ms = 0;
  float roll = 0, pitch = 0, yaw = 0;                 // rad, FRD body in NED
  float rollspeed = 0, pitchspeed = 0, yawspeed = 0;  // rad/s, FRD body axes
};

struct AttitudeQuaternion {
  std::uint32_t time_boot_ms = 0;
  float q1 = 1, q2 = 0, q3 = 0, q4 = 0;  // w, x, y, z: FRD body to NED
  float rollspeed = 0, pitchspeed = 0, yawspeed = 0;
  std::array<float, 4> repr_offset_q{};
};

// The autopilot's local position and velocity estimate (from whatever aids its filter: optical
// flow, VIO, GPS, or our own VISION_POSITION_ESTIMATE).
struct LocalPositionNed {
  std::uint32_t time_boot_ms = 0;
  float x = 0, y = 0, z = 0;     // m, local NED
  float vx = 0, vy = 0, vz = 0;  // m/s, local NED
};

struct HighresImu {
  std::uint64_t time_usec = 0;
  float xacc = 0, yacc = 0, zacc = 0;     // m/s^2, FRD body, specific force (gravity included)
  float xgyro = 0, ygyro = 0, zgyro = 0;  // rad/s, FRD body
  float xmag = 0, ymag = 0, zmag = 0;
  float abs_pressure = 0, diff_pressure = 0, pressure_alt = 0, temperature = 0;
  std::uint16_t fields_updated = 0;
  std::uint8_t id = 0;
};

// tc1 == 0: a request carrying the sender's time ts1; otherwise the answer: tc1 the answerer's
// time, ts1 the request's ts1 echoed. Nanoseconds.
struct Timesync {
  std::int64_t tc1 = 0;
  std::int64_t ts1 = 0;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
};

// A command with up to seven parameters (their meaning set by the command); confirmation 0 on
// the first transmission, counting up on each resend.
struct CommandLong {
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;  // 0: every component
  std::uint16_t command = 0;
  std::uint8_t confirmation = 0;
  float param1 = 0, param2 = 0, param3 = 0, param4 = 0, param5 = 0, param6 = 0, param7 = 0;
};

// The answer to a command. target_*: the command's sender (0 from senders predating them).
struct CommandAck {
  std::uint16_t command = 0;
  std::uint8_t result = kMavResultAccepted;
  std::uint8_t progress = 0;  // percent while kMavResultInProgress
  std::int32_t result_param2 = 0;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
};

struct VisionPositionEstimate {
  std::uint64_t usec = 0;
  float x = 0, y = 0, z = 0;           // m, local NED
  float roll = 0, pitch = 0, yaw = 0;  // rad, FRD body in NED
  std::array<float, 21> covariance{};  // upper triangle of the 6x6, row-major; [0] NaN: unknown
  std::uint8_t reset_counter = 0;
};

struct Odometry {
  std::uint64_t time_usec = 0;
  std::uint8_t frame_id = kMavFrameLocalNed;
  std::uint8_t child_frame_id = kMavFrameBodyFrd;
  float x = 0, y = 0, z = 0;
  std::array<float, 4> q{1, 0, 0, 0};  // w, x, y, z: child frame to frame_id
  float vx = 0, vy = 0, vz = 0, rollspeed = 0, pitchspeed = 0, yawspeed = 0;
  std::array<float, 21> pose_covariance{};
  std::array<float, 21> velocity_covariance{};
  std::uint8_t reset_counter = 0;
  std::uint8_t estimator_type = 0;
  std::int8_t quality = 0;  // 0: unknown/unset, 1..100
};

using Payload = std::vector<std::uint8_t>;

Payload encode(const Heartbeat& m);
Payload encode(const SystemTime& m);
Payload encode(const Attitude& m);
Payload encode(const AttitudeQuaternion& m);
Payload encode(const LocalPositionNed& m);
Payload encode(const HighresImu& m);
Payload encode(const Timesync& m);
Payload encode(const CommandLong& m);
Payload encode(const CommandAck& m);
Payload encode(const VisionPositionEstimate& m);
Payload encode(const Odometry& m);

Heartbeat decode_heartbeat(const Payload& p);
SystemTime decode_system_time(const Payload& p);
Attitude decode_attitude(const Payload& p);
AttitudeQuaternion decode_attitude_quaternion(const Payload& p);
LocalPositionNed decode_local_position_ned(const Payload& p);
HighresImu decode_highres_imu(const Payload& p);
Timesync decode_timesync(const Payload& p);
CommandLong decode_command_long(const Payload& p);
CommandAck decode_command_ack(const Payload& p);
VisionPositionEstimate decode_vision_position_estimate(const Payload& p);
Odometry decode_odometry(const Payload& p);

}  // namespace uavslam::mavlink
