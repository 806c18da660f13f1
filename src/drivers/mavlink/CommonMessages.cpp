#include "drivers/mavlink/CommonMessages.hpp"

#include <map>
#include <stdexcept>

namespace uavslam::mavlink {
namespace {

FieldDefinition base(const char* type, const char* name, std::size_t array_length = 0) {
  return {type, name, array_length, false};
}
FieldDefinition extension(const char* type, const char* name, std::size_t array_length = 0) {
  return {type, name, array_length, true};
}

// Transcribed from common.xml, fields in XML order.
std::map<std::uint32_t, MessageDefinition> make_definitions() {
  std::map<std::uint32_t, MessageDefinition> all;
  const auto add = [&all](std::uint32_t id, const char* name, std::vector<FieldDefinition> fields) {
    all.emplace(id, MessageDefinition(id, name, std::move(fields)));
  };
  add(kHeartbeat, "HEARTBEAT",
      {base("uint8_t", "type"), base("uint8_t", "autopilot"), base("uint8_t", "base_mode"),
       base("uint32_t", "custom_mode"), base("uint8_t", "system_status"),
       base("uint8_t_mavlink_version", "mavlink_version")});
  add(kSystemTime, "SYSTEM_TIME",
      {base("uint64_t", "time_unix_usec"), base("uint32_t", "time_boot_ms")});
  add(kAttitude, "ATTITUDE",
      {base("uint32_t", "time_boot_ms"), base("float", "roll"), base("float", "pitch"),
       base("float", "yaw"), base("float", "rollspeed"), base("float", "pitchspeed"),
       base("float", "yawspeed")});
  add(kAttitudeQuaternion, "ATTITUDE_QUATERNION",
      {base("uint32_t", "time_boot_ms"), base("float", "q1"), base("float", "q2"),
       base("float", "q3"), base("float", "q4"), base("float", "rollspeed"),
       base("float", "pitchspeed"), base("float", "yawspeed"),
       extension("float", "repr_offset_q", 4)});
  add(kLocalPositionNed, "LOCAL_POSITION_NED",
      {base("uint32_t", "time_boot_ms"), base("float", "x"), base("float", "y"), base("float", "z"),
       base("float", "vx"), base("float", "vy"), base("float", "vz")});
  add(kCommandLong, "COMMAND_LONG",
      {base("uint8_t", "target_system"), base("uint8_t", "target_component"),
       base("uint16_t", "command"), base("uint8_t", "confirmation"), base("float", "param1"),
       base("float", "param2"), base("float", "param3"), base("float", "param4"),
       base("float", "param5"), base("float", "param6"), base("float", "param7")});
  add(kCommandAck, "COMMAND_ACK",
      {base("uint16_t", "command"), base("uint8_t", "result"), extension("uint8_t", "progress"),
       extension("int32_t", "result_param2"), extension("uint8_t", "target_system"),
       extension("uint8_t", "target_component")});
  add(kVisionPositionEstimate, "VISION_POSITION_ESTIMATE",
      {base("uint64_t", "usec"), base("float", "x"), base("float", "y"), base("float", "z"),
       base("float", "roll"), base("float", "pitch"), base("float", "yaw"),
       extension("float", "covariance", 21), extension("uint8_t", "reset_counter")});
  add(kHighresImu, "HIGHRES_IMU",
      {base("uint64_t", "time_usec"), base("float", "xacc"), base("float", "yacc"),
       base("float", "zacc"), base("float", "xgyro"), base("float", "ygyro"),
       base("float", "zgyro"), base("float", "xmag"), base("float", "ymag"), base("float", "zmag"),
       base("float", "abs_pressure"), base("float", "diff_pressure"), base("float", "pressure_alt"),
       base("float", "temperature"), base("uint16_t", "fields_updated"),
       extension("uint8_t", "id")});
  add(kTimesync, "TIMESYNC",
      {base("int64_t", "tc1"), base("int64_t", "ts1"), extension("uint8_t", "target_system"),
       extension("uint8_t", "target_component")});
  add(kOdometry, "ODOMETRY",
      {base("uint64_t", "time_usec"), base("uint8_t", "frame_id"),
       base("uint8_t", "child_frame_id"), base("float", "x"), base("float", "y"),
       base("float", "z"), base("float", "q", 4), base("float", "vx"), base("float", "vy"),
       base("float", "vz"), base("float", "rollspeed"), base("float", "pitchspeed"),
       base("float", "yawspeed"), base("float", "pose_covariance", 21),
       base("float", "velocity_covariance", 21), extension("uint8_t", "reset_counter"),
       extension("uint8_t", "estimator_type"), extension("int8_t", "quality")});
  return all;
}

const std::map<std::uint32_t, MessageDefinition>& definitions() {
  static const std::map<std::uint32_t, MessageDefinition> all = make_definitions();
  return all;
}

}  // namespace

const MessageDefinition* find_definition(std::uint32_t id) {
  const auto found = definitions().find(id);
  return found == definitions().end() ? nullptr : &found->second;
}

const MessageDefinition& definition(MessageId id) {
  return definitions().at(id);
}

}  // namespace uavslam::mavlink
