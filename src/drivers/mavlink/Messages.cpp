#include "drivers/mavlink/Messages.hpp"

#include <iterator>

#include "drivers/mavlink/CommonMessages.hpp"
#include "drivers/mavlink/Payload.hpp"

namespace uavslam::mavlink {
namespace {

// Writes fields by name at the offsets the message's definition derives.
class FieldWriter {
 public:
  explicit FieldWriter(MessageId id) : message_(definition(id)), out_(message_.full_length()) {}
  template <typename T>
  FieldWriter& set(const char* name, T value) {
    out_.put(message_.offset(name), value);
    return *this;
  }
  template <typename T, std::size_t N>
  FieldWriter& set(const char* name, const std::array<T, N>& values) {
    const std::size_t offset = message_.offset(name);
    for (std::size_t i = 0; i < N; ++i) out_.put(offset + i * sizeof(T), values[i]);
    return *this;
  }
  Payload payload() const { return out_.bytes(); }

 private:
  const MessageDefinition& message_;
  PayloadWriter out_;
};

class FieldReader {
 public:
  FieldReader(MessageId id, const Payload& payload) : message_(definition(id)), in_(payload) {}
  template <typename T>
  T get(const char* name) const {
    return in_.get<T>(message_.offset(name));
  }
  template <typename T, std::size_t N>
  std::array<T, N> get_array(const char* name) const {
    std::array<T, N> values{};
    const std::size_t offset = message_.offset(name);
    for (std::size_t i = 0; i < N; ++i) values[i] = in_.get<T>(offset + i * sizeof(T));
    return values;
  }

 private:
  const MessageDefinition& message_;
  PayloadReader in_;
};

}  // namespace

std::string mav_result_name(std::uint8_t result) {
  static const char* const kNames[] = {"MAV_RESULT_ACCEPTED", "MAV_RESULT_TEMPORARILY_REJECTED",
                                       "MAV_RESULT_DENIED",   "MAV_RESULT_UNSUPPORTED",
                                       "MAV_RESULT_FAILED",   "MAV_RESULT_IN_PROGRESS",
                                       "MAV_RESULT_CANCELLED"};
  if (result < std::size(kNames)) return kNames[result];
  return "MAV_RESULT " + std::to_string(result);
}

Payload encode(const Heartbeat& m) {
  return FieldWriter(kHeartbeat)
      .set("type", m.type)
      .set("autopilot", m.autopilot)
      .set("base_mode", m.base_mode)
      .set("custom_mode", m.custom_mode)
      .set("system_status", m.system_status)
      .set("mavlink_version", m.mavlink_version)
      .payload();
}

Payload encode(const SystemTime& m) {
  return FieldWriter(kSystemTime)
      .set("time_unix_usec", m.time_unix_usec)
      .set("time_boot_ms", m.time_boot_ms)
      .payload();
}

Payload encode(const Attitude& m) {
  return FieldWriter(kAttitude)
      .set("time_boot_ms", m.time_boot_ms)
      .set("roll", m.roll)
      .set("pitch", m.pitch)
      .set("yaw", m.yaw)
      .set("rollspeed", m.rollspeed)
      .set("pitchspeed", m.pitchspeed)
      .set("yawspeed", m.yawspeed)
      .payload();
}

Payload encode(const AttitudeQuaternion& m) {
  return FieldWriter(kAttitudeQuaternion)
      .set("time_boot_ms", m.time_boot_ms)
      .set("q1", m.q1)
      .set("q2", m.q2)
      .set("q3", m.q3)
      .set("q4", m.q4)
      .set("rollspeed", m.rollspeed)
      .set("pitchspeed", m.pitchspeed)
      .set("yawspeed", m.yawspeed)
      .set("repr_offset_q", m.repr_offset_q)
      .payload();
}

Payload encode(const LocalPositionNed& m) {
  return FieldWriter(kLocalPositionNed)
      .set("time_boot_ms", m.time_boot_ms)
      .set("x", m.x)
      .set("y", m.y)
      .set("z", m.z)
      .set("vx", m.vx)
      .set("vy", m.vy)
      .set("vz", m.vz)
      .payload();
}

Payload encode(const HighresImu& m) {
  return FieldWriter(kHighresImu)
      .set("time_usec", m.time_usec)
      .set("xacc", m.xacc)
      .set("yacc", m.yacc)
      .set("zacc", m.zacc)
      .set("xgyro", m.xgyro)
      .set("ygyro", m.ygyro)
      .set("zgyro", m.zgyro)
      .set("xmag", m.xmag)
      .set("ymag", m.ymag)
      .set("zmag", m.zmag)
      .set("abs_pressure", m.abs_pressure)
      .set("diff_pressure", m.diff_pressure)
      .set("pressure_alt", m.pressure_alt)
      .set("temperature", m.temperature)
      .set("fields_updated", m.fields_updated)
      .set("id", m.id)
      .payload();
}

Payload encode(const Timesync& m) {
  return FieldWriter(kTimesync)
      .set("tc1", m.tc1)
      .set("ts1", m.ts1)
      .set("target_system", m.target_system)
      .set("target_component", m.target_component)
      .payload();
}

Payload encode(const CommandLong& m) {
  return FieldWriter(kCommandLong)
      .set("target_system", m.target_system)
      .set("target_component", m.target_component)
      .set("command", m.command)
      .set("confirmation", m.confirmation)
      .set("param1", m.param1)
      .set("param2", m.param2)
      .set("param3", m.param3)
      .set("param4", m.param4)
      .set("param5", m.param5)
      .set("param6", m.param6)
      .set("param7", m.param7)
      .payload();
}

Payload encode(const CommandAck& m) {
  return FieldWriter(kCommandAck)
      .set("command", m.command)
      .set("result", m.result)
      .set("progress", m.progress)
      .set("result_param2", m.result_param2)
      .set("target_system", m.target_system)
      .set("target_component", m.target_component)
      .payload();
}

Payload encode(const VisionPositionEstimate& m) {
  return FieldWriter(kVisionPositionEstimate)
      .set("usec", m.usec)
      .set("x", m.x)
      .set("y", m.y)
      .set("z", m.z)
      .set("roll", m.roll)
      .set("pitch", m.pitch)
      .set("yaw", m.yaw)
      .set("covariance", m.covariance)
      .set("reset_counter", m.reset_counter)
      .payload();
}

Payload encode(const Odometry& m) {
  return FieldWriter(kOdometry)
      .set("time_usec", m.time_usec)
      .set("frame_id", m.frame_id)
      .set("child_frame_id", m.child_frame_id)
      .set("x", m.x)
      .set("y", m.y)
      .set("z", m.z)
      .set("q", m.q)
      .set("vx", m.vx)
      .set("vy", m.vy)
      .set("vz", m.vz)
      .set("rollspeed", m.rollspeed)
      .set("pitchspeed", m.pitchspeed)
      .set("yawspeed", m.yawspeed)
      .set("pose_covariance", m.pose_covariance)
      .set("velocity_covariance", m.velocity_covariance)
      .set("reset_counter", m.reset_counter)
      .set("estimator_type", m.estimator_type)
      .set("quality", m.quality)
      .payload();
}

Heartbeat decode_heartbeat(const Payload& p) {
  const FieldReader r(kHeartbeat, p);
  Heartbeat m;
  m.type = r.get<std::uint8_t>("type");
  m.autopilot = r.get<std::uint8_t>("autopilot");
  m.base_mode = r.get<std::uint8_t>("base_mode");
  m.custom_mode = r.get<std::uint32_t>("custom_mode");
  m.system_status = r.get<std::uint8_t>("system_status");
  m.mavlink_version = r.get<std::uint8_t>("mavlink_version");
  return m;
}

SystemTime decode_system_time(const Payload& p) {
  const FieldReader r(kSystemTime, p);
  return {r.get<std::uint64_t>("time_unix_usec"), r.get<std::uint32_t>("time_boot_ms")};
}

Attitude decode_attitude(const Payload& p) {
  const FieldReader r(kAttitude, p);
  Attitude m;
  m.time_boot_ms = r.get<std::uint32_t>("time_boot_ms");
  m.roll = r.get<float>("roll");
  m.pitch = r.get<float>("pitch");
  m.yaw = r.get<float>("yaw");
  m.rollspeed = r.get<float>("rollspeed");
  m.pitchspeed = r.get<float>("pitchspeed");
  m.yawspeed = r.get<float>("yawspeed");
  return m;
}

AttitudeQuaternion decode_attitude_quaternion(const Payload& p) {
  const FieldReader r(kAttitudeQuaternion, p);
  AttitudeQuaternion m;
  m.time_boot_ms = r.get<std::uint32_t>("time_boot_ms");
  m.q1 = r.get<float>("q1");
  m.q2 = r.get<float>("q2");
  m.q3 = r.get<float>("q3");
  m.q4 = r.get<float>("q4");
  m.rollspeed = r.get<float>("rollspeed");
  m.pitchspeed = r.get<float>("pitchspeed");
  m.yawspeed = r.get<float>("yawspeed");
  m.repr_offset_q = r.get_array<float, 4>("repr_offset_q");
  return m;
}

LocalPositionNed decode_local_position_ned(const Payload& p) {
  const FieldReader r(kLocalPositionNed, p);
  LocalPositionNed m;
  m.time_boot_ms = r.get<std::uint32_t>("time_boot_ms");
  m.x = r.get<float>("x");
  m.y = r.get<float>("y");
  m.z = r.get<float>("z");
  m.vx = r.get<float>("vx");
  m.vy = r.get<float>("vy");
  m.vz = r.get<float>("vz");
  return m;
}

HighresImu decode_highres_imu(const Payload& p) {
  const FieldReader r(kHighresImu, p);
  HighresImu m;
  m.time_usec = r.get<std::uint64_t>("time_usec");
  m.xacc = r.get<float>("xacc");
  m.yacc = r.get<float>("yacc");
  m.zacc = r.get<float>("zacc");
  m.xgyro = r.get<float>("xgyro");
  m.ygyro = r.get<float>("ygyro");
  m.zgyro = r.get<float>("zgyro");
  m.xmag = r.get<float>("xmag");
  m.ymag = r.get<float>("ymag");
  m.zmag = r.get<float>("zmag");
  m.abs_pressure = r.get<float>("abs_pressure");
  m.diff_pressure = r.get<float>("diff_pressure");
  m.pressure_alt = r.get<float>("pressure_alt");
  m.temperature = r.get<float>("temperature");
  m.fields_updated = r.get<std::uint16_t>("fields_updated");
  m.id = r.get<std::uint8_t>("id");
  return m;
}

Timesync decode_timesync(const Payload& p) {
  const FieldReader r(kTimesync, p);
  return {r.get<std::int64_t>("tc1"), r.get<std::int64_t>("ts1"),
          r.get<std::uint8_t>("target_system"), r.get<std::uint8_t>("target_component")};
}

CommandLong decode_command_long(const Payload& p) {
  const FieldReader r(kCommandLong, p);
  CommandLong m;
  m.target_system = r.get<std::uint8_t>("target_system");
  m.target_component = r.get<std::uint8_t>("target_component");
  m.command = r.get<std::uint16_t>("command");
  m.confirmation = r.get<std::uint8_t>("confirmation");
  m.param1 = r.get<float>("param1");
  m.param2 = r.get<float>("param2");
  m.param3 = r.get<float>("param3");
  m.param4 = r.get<float>("param4");
  m.param5 = r.get<float>("param5");
  m.param6 = r.get<float>("param6");
  m.param7 = r.get<float>("param7");
  return m;
}

CommandAck decode_command_ack(const Payload& p) {
  const FieldReader r(kCommandAck, p);
  CommandAck m;
  m.command = r.get<std::uint16_t>("command");
  m.result = r.get<std::uint8_t>("result");
  m.progress = r.get<std::uint8_t>("progress");
  m.result_param2 = r.get<std::int32_t>("result_param2");
  m.target_system = r.get<std::uint8_t>("target_system");
  m.target_component = r.get<std::uint8_t>("target_component");
  return m;
}

VisionPositionEstimate decode_vision_position_estimate(const Payload& p) {
  const FieldReader r(kVisionPositionEstimate, p);
  VisionPositionEstimate m;
  m.usec = r.get<std::uint64_t>("usec");
  m.x = r.get<float>("x");
  m.y = r.get<float>("y");
  m.z = r.get<float>("z");
  m.roll = r.get<float>("roll");
  m.pitch = r.get<float>("pitch");
  m.yaw = r.get<float>("yaw");
  m.covariance = r.get_array<float, 21>("covariance");
  m.reset_counter = r.get<std::uint8_t>("reset_counter");
  return m;
}

Odometry decode_odometry(const Payload& p) {
  const FieldReader r(kOdometry, p);
  Odometry m;
  m.time_usec = r.get<std::uint64_t>("time_usec");
  m.frame_id = r.get<std::uint8_t>("frame_id");
  m.child_frame_id = r.get<std::uint8_t>("child_frame_id");
  m.x = r.get<float>("x");
  m.y = r.get<float>("y");
  m.z = r.get<float>("z");
  m.q = r.get_array<float, 4>("q");
  m.vx = r.get<float>("vx");
  m.vy = r.get<float>("vy");
  m.vz = r.get<float>("vz");
  m.rollspeed = r.get<float>("rollspeed");
  m.pitchspeed = r.get<float>("pitchspeed");
  m.yawspeed = r.get<float>("yawspeed");
  m.pose_covariance = r.get_array<float, 21>("pose_covariance");
  m.velocity_covariance = r.get_array<float, 21>("velocity_covariance");
  m.reset_counter = r.get<std::uint8_t>("reset_counter");
  m.estimator_type = r.get<std::uint8_t>("estimator_type");
  m.quality = r.get<std::int8_t>("quality");
  return m;
}

}  // namespace uavslam::mavlink
