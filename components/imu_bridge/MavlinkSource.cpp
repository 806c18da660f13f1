#include "imu_bridge/MavlinkSource.hpp"

#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <system_error>

#include <msg/ImuPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <msg/TwistPubSubTypes.h>

#include "common/IncompatibleQos.hpp"
#include "common/StopRequest.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "drivers/mavlink/AutopilotSession.hpp"
#include "drivers/mavlink/SerialLink.hpp"
#include "drivers/mavlink/UdpLink.hpp"

namespace uavslam::process {
namespace {

constexpr char kPrefix[] = "mavlink:";
constexpr int kReceiveTimeoutMs = 20;
constexpr double kMaxStreamRate = 1000.0;  // Hz: an interval of 1 ms

double host_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

struct LinkAddress {
  bool udp = true;
  int port = 0;
  std::string device;
  int baud = 0;
};

bool parse_int(const std::string& text, int& value) {
  try {
    std::size_t used = 0;
    value = std::stoi(text, &used);
    return used == text.size() && value > 0;
  } catch (const std::exception&) {
    return false;
  }
}

std::optional<LinkAddress> parse_source(const std::string& source) {
  if (source.rfind(kPrefix, 0) != 0) return std::nullopt;
  const std::string rest = source.substr(sizeof(kPrefix) - 1);
  LinkAddress address;
  if (rest.rfind("udp:", 0) == 0) {
    if (!parse_int(rest.substr(4), address.port) || address.port > 65535) return std::nullopt;
    return address;
  }
  const std::size_t baud_at = rest.rfind(':');
  if (rest.rfind("serial:", 0) != 0 || baud_at <= 7) return std::nullopt;
  address.udp = false;
  address.device = rest.substr(7, baud_at - 7);
  if (!parse_int(rest.substr(baud_at + 1), address.baud)) return std::nullopt;
  return address;
}

std::unique_ptr<mavlink::ByteLink> open_link(const LinkAddress& address,
                                             const MavlinkOptions& options) {
  try {
    if (address.udp) return std::make_unique<mavlink::UdpLink>(options.bind_address, address.port);
    return std::make_unique<mavlink::SerialLink>(address.device, address.baud);
  } catch (const std::exception& e) {
    throw io::ConfigError(std::string("source: ") + e.what());
  }
}

mavlink::PoseEstimate estimate_of(const msg::PoseWithCovarianceStamped& message) {
  mavlink::PoseEstimate estimate;
  estimate.pose = dds::from_msg(message);
  std::copy(std::begin(message.covariance()), std::end(message.covariance()),
            estimate.covariance.begin());
  estimate.quality = message.quality();
  estimate.scan_seq = message.scan_seq();
  return estimate;
}

void print_status(const mavlink::AutopilotSession& session, const std::string& link, double seconds,
                  std::uint64_t frames_before) {
  const mavlink::FrameCounts& f = session.frame_counts();
  const mavlink::SessionCounts& s = session.counts();
  std::cerr << "imu_bridge: mavlink " << link << ": "
            << static_cast<double>(f.frames - frames_before) / seconds << " messages/s, "
            << f.frames << " frames (" << f.v1_frames << " v1, " << f.signed_frames << " signed), "
            << f.crc_errors << " CRC errors, " << f.sequence_gaps << " sequence gaps, "
            << f.garbage_bytes << " garbage bytes, " << f.unknown_messages << " unknown messages, "
            << s.heartbeats << " heartbeats, " << s.imu_samples << " imu samples, time offset ";
  if (session.clock().round_trips() > 0) {
    std::cerr << std::fixed << std::setprecision(6) << session.clock().offset() << std::defaultfloat
              << " s (drift " << session.clock().drift_ppm() << " ppm, round trip "
              << session.clock().last_round_trip() * 1e3 << " ms)";
  } else {
    std::cerr << "unknown";
  }
  const mavlink::IntervalRequestCounts& r = s.interval_requests;
  std::cerr << ", " << s.poses_sent << " poses sent (" << s.poses_withheld
            << " dead-reckoned withheld), " << r.sent << " stream requests (" << r.accepted
            << " accepted, " << r.refused << " refused, " << r.unanswered << " unanswered), "
            << s.reboots << " autopilot reboots\n";
}

std::string stream_rate(double hz) {
  std::ostringstream text;
  if (hz > 0) {
    text << hz << " Hz";
  } else {
    text << "the autopilot's own rate of";
  }
  return text.str();
}

void print_reports(mavlink::AutopilotSession& session) {
  for (const std::string& line : session.take_reports()) {
    std::cerr << "imu_bridge: mavlink: " << line << "\n";
  }
}

}  // namespace

void add_mavlink_options(CLI::App& app, MavlinkOptions& options) {
  app.add_option("--mavlink-bind", options.bind_address,
                 "mavlink:udp: the local address the UDP port is bound on (real use: the "
                 "companion link's interface)")
      ->capture_default_str();
  app.add_option("--mavlink-pose", options.pose_message,
                 "mavlink: send the pose as VISION_POSITION_ESTIMATE (vision) or ODOMETRY "
                 "(odometry)")
      ->check(CLI::IsMember({"vision", "odometry"}))
      ->capture_default_str();
  app.add_option("--mavlink-status-period", options.status_period,
                 "mavlink: seconds between status lines on stderr")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--mavlink-attitude-rate", options.attitude_rate,
                 "mavlink: Hz of ATTITUDE_QUATERNION to ask the autopilot for "
                 "(MAV_CMD_SET_MESSAGE_INTERVAL); 0: leave the autopilot's own rate")
      ->check(CLI::Range(0.0, kMaxStreamRate))
      ->capture_default_str();
  app.add_option("--mavlink-imu-rate", options.imu_rate,
                 "mavlink: Hz of HIGHRES_IMU to ask the autopilot for; 0: leave the autopilot's "
                 "own rate")
      ->check(CLI::Range(0.0, kMaxStreamRate))
      ->capture_default_str();
  app.add_option("--mavlink-velocity-sigma", options.velocity_sigma,
                 "mavlink: publish the autopilot's velocity (LOCAL_POSITION_NED) on `velocity`, "
                 "stated to this many m/s; 0: not. Only where the autopilot's velocity comes from "
                 "its own optical flow or VIO, not from the poses it gets from us")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--mavlink-velocity-rate", options.velocity_rate,
                 "mavlink: Hz of LOCAL_POSITION_NED to ask the autopilot for, when its velocity "
                 "is published; 0: leave the autopilot's own rate")
      ->check(CLI::Range(0.0, kMaxStreamRate))
      ->capture_default_str();
}

std::vector<std::string> mavlink_config_keys() {
  return {"mavlink_bind",          "mavlink_pose",     "mavlink_status_period",
          "mavlink_attitude_rate", "mavlink_imu_rate", "mavlink_velocity_sigma",
          "mavlink_velocity_rate"};
}

void apply_mavlink_config(const CLI::App& app, const io::YamlReader& section,
                          MavlinkOptions& options) {
  if (unset(app, "--mavlink-bind")) {
    options.bind_address = section.get_string_or("mavlink_bind", options.bind_address);
  }
  if (unset(app, "--mavlink-pose") && section.has("mavlink_pose")) {
    const io::YamlReader pose = section.at("mavlink_pose");
    options.pose_message = pose.as_string();
    if (options.pose_message != "vision" && options.pose_message != "odometry") {
      pose.fail_expected("vision or odometry");
    }
  }
  if (unset(app, "--mavlink-status-period")) {
    options.status_period = section.get_double_or("mavlink_status_period", options.status_period,
                                                  io::NumberRange::positive());
  }
  if (unset(app, "--mavlink-attitude-rate")) {
    options.attitude_rate = section.get_double_or("mavlink_attitude_rate", options.attitude_rate,
                                                  io::NumberRange::between(0.0, kMaxStreamRate));
  }
  if (unset(app, "--mavlink-imu-rate")) {
    options.imu_rate = section.get_double_or("mavlink_imu_rate", options.imu_rate,
                                             io::NumberRange::between(0.0, kMaxStreamRate));
  }
  if (unset(app, "--mavlink-velocity-sigma")) {
    options.velocity_sigma = section.get_double_or("mavlink_velocity_sigma", options.velocity_sigma,
                                                   io::NumberRange::non_negative());
  }
  if (unset(app, "--mavlink-velocity-rate")) {
    options.velocity_rate = section.get_double_or("mavlink_velocity_rate", options.velocity_rate,
                                                  io::NumberRange::between(0.0, kMaxStreamRate));
  }
}

bool is_mavlink_source(const std::string& source) {
  return source.rfind(kPrefix, 0) == 0;
}

std::string mavlink_source_problem(const std::string& source) {
  if (parse_source(source)) return {};
  return "expected mavlink:udp:PORT or mavlink:serial:DEVICE:BAUD, got '" + source + "'";
}

int bridge_autopilot(const NodeOptions& node, const SimSourceOptions& source,
                     const MavlinkOptions& options) {
  const std::optional<LinkAddress> address = parse_source(source.source);
  if (!address) throw io::ConfigError("source: " + mavlink_source_problem(source.source));
  const std::unique_ptr<mavlink::ByteLink> link = open_link(*address, options);
  mavlink::SessionOptions session_options;
  if (options.pose_message == "odometry") {
    session_options.pose_message = mavlink::PoseMessage::kOdometry;
  }
  session_options.attitude_rate = options.attitude_rate;
  session_options.imu_rate = options.imu_rate;
  session_options.velocity_sigma = options.velocity_sigma;
  session_options.velocity_rate = options.velocity_rate;
  mavlink::AutopilotSession session(session_options);
  std::mutex session_mutex;  // the session and link: main loop vs the pose reader's thread
  const mavlink::AutopilotSession::Send send = [&link](const std::vector<std::uint8_t>& bytes) {
    link->send(bytes);
  };

  dds::Participant participant(node.domain, profiles_path(node), node.participant_profile,
                               "imu_bridge");
  std::optional<dds::Writer<msg::TwistWithCovarianceStampedPubSubType>> velocity;
  if (options.velocity_sigma > 0.0) {
    velocity.emplace(participant, dds::topic_name(node.vehicle, dds::kVelocityTopic),
                     node.profile(dds::kVelocityTopic, "sensor_writer"));
  }
  dds::Writer<msg::ImuPubSubType> writer(participant, dds::topic_name(node.vehicle, dds::kImuTopic),
                                         node.profile(dds::kImuTopic, "sensor_writer"));
  dds::Reader<msg::PoseWithCovarianceStampedPubSubType> poses(
      participant, dds::topic_name(node.vehicle, dds::kPoseTopic),
      node.profile(dds::kPoseTopic, "state_reader"),
      [&](const msg::PoseWithCovarianceStamped& message, const auto&) {
        const std::lock_guard<std::mutex> lock(session_mutex);
        session.send_pose(estimate_of(message), send);
      });
  std::cerr << "imu_bridge: publishing " << writer.topic() << " from the autopilot on "
            << link->description() << ", sending " << poses.topic() << " back as "
            << (options.pose_message == "odometry" ? "ODOMETRY" : "VISION_POSITION_ESTIMATE")
            << " (domain " << node.domain << "); asking for " << stream_rate(options.attitude_rate)
            << " ATTITUDE_QUATERNION and " << stream_rate(options.imu_rate) << " HIGHRES_IMU";
  if (velocity) {
    std::cerr << "; publishing " << velocity->topic() << " from "
              << stream_rate(options.velocity_rate) << " LOCAL_POSITION_NED, stated to "
              << options.velocity_sigma << " m/s";
  }
  std::cerr << "\n";

  const dds::Source imu_source{"imu", node.vehicle};
  std::uint64_t seq = 0;
  QosWatch qos("imu_bridge");
  const mavlink::AutopilotSession::OnImu publish = [&](const ImuSample& sample) {
    qos.output(writer);
    writer.write(dds::to_msg(sample, seq++, imu_source));
  };
  std::uint64_t velocity_seq = 0;
  const mavlink::AutopilotSession::OnVelocity publish_velocity = [&](const VelocitySample& sample) {
    if (!velocity) return;
    qos.output(*velocity);
    velocity->write(dds::to_msg(sample, velocity_seq++, imu_source));
  };
  std::vector<std::uint8_t> buffer(4096);
  bool heard = false;
  double next_status = host_now() + options.status_period;
  std::uint64_t frames_at_status = 0;
  while (!stop_requested()) {
    qos.input(poses);
    const std::size_t got = link->receive(buffer.data(), buffer.size(), kReceiveTimeoutMs);
    const double now = host_now();
    const std::lock_guard<std::mutex> lock(session_mutex);
    session.receive(buffer.data(), got, now, publish, send, publish_velocity);
    session.tick(now, send);
    if (!heard && session.autopilot_heard()) {
      heard = true;
      std::cerr << "imu_bridge: autopilot heard on " << link->description() << "\n";
    }
    print_reports(session);
    if (now >= next_status) {
      print_status(session, link->description(), options.status_period, frames_at_status);
      frames_at_status = session.frame_counts().frames;
      next_status = now + options.status_period;
    }
  }
  const std::lock_guard<std::mutex> lock(session_mutex);
  print_status(session, link->description(), options.status_period, frames_at_status);
  std::cerr << "imu_bridge: published " << seq << " samples from the autopilot";
  if (velocity) std::cerr << " and " << velocity_seq << " velocities";
  std::cerr << " (stopped)\n";
  return qos.exit_code();
}

}  // namespace uavslam::process
