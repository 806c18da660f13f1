// autopilot_emulator: a small stand-in for a PX4/ArduPilot autopilot on a companion UDP link, for
// imu_bridge's tests. It flies a scenario with the simulator (src/sim) and sends, to
// 127.0.0.1:PORT only, what an autopilot streams: HIGHRES_IMU and ATTITUDE_QUATERNION per IMU
// sample (ATTITUDE every 20th), HEARTBEAT and SYSTEM_TIME once a second, all stamped with its own
// boot clock (offset and drift settable). It answers TIMESYNC requests, and records the
// VISION_POSITION_ESTIMATE / ODOMETRY it receives to a file, one line each. Faults on request:
// MAVLink 1 frames, signed frames, corrupted checksums, garbage bytes, lost frames. With
// --local-position it also sends LOCAL_POSITION_NED every 10th IMU sample: the flight's true
// velocity in the attitude's drifting heading frame (as from the autopilot's own optical flow).
// It answers every COMMAND_LONG addressed to it with a COMMAND_ACK: MAV_CMD_SET_MESSAGE_INTERVAL
// for a message it can stream ACCEPTED (DENIED with --refuse-intervals or for another message),
// any other command UNSUPPORTED; --ignore-commands answers none. With --streams-on-request it
// sends only HEARTBEAT and SYSTEM_TIME until asked, then each message asked for at the interval
// asked (at most one per IMU sample), as an autopilot whose port streams nothing by default;
// otherwise its streams stay as above whatever is asked. The summary line on stdout says what
// was asked of it.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>

#include "drivers/mavlink/CommonMessages.hpp"
#include "drivers/mavlink/FrameConventions.hpp"
#include "drivers/mavlink/FrameReader.hpp"
#include "drivers/mavlink/FrameWriter.hpp"
#include "drivers/mavlink/Messages.hpp"
#include "io/ScenarioFile.hpp"
#include "sim/FlightSimulator.hpp"
#include "sim/ImuSimulator.hpp"

namespace uavslam::mavlink {
namespace {

volatile std::sig_atomic_t stop_signal = 0;
void request_stop(int) {
  stop_signal = 1;
}

double host_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

struct EmulatorOptions {
  int port = 14550;
  std::string scenario = "config/scenarios/short.yaml";
  double duration = 5.0;    // s of the flight
  double start_at = 0.0;    // host time of the flight's first sample; 0: now + 0.5 s
  double boot_age = 100.0;  // s the autopilot had been running at the flight's start
  double drift_ppm = 0.0;
  double linger = 0.0;  // s to keep listening after the flight
  bool v1 = false;
  bool sign = false;
  int bad_crc_every = 0;
  int garbage_every = 0;
  int drop_every = 0;
  bool streams_on_request = false;
  bool refuse_intervals = false;
  bool ignore_commands = false;
  bool local_position = false;
  std::string record;
};

// Our system and component ids, and the messages we can stream.
constexpr std::uint8_t kSystemId = 1;
constexpr std::uint8_t kComponentId = 1;
bool streamable(std::uint32_t id) {
  return id == kAttitude || id == kAttitudeQuaternion || id == kHighresImu ||
         id == kLocalPositionNed;
}

// A stream asked for with SET_MESSAGE_INTERVAL, in flight time (s).
struct Stream {
  double interval = 0;  // 0: not sent
  double next_due = 0;
};

struct Tally {
  int attitude_sent = 0, dropped = 0, corrupted = 0, garbage_bursts = 0;
  int timesync_answered = 0, heartbeats_heard = 0, poses = 0;
  int highres_imu_sent = 0, interval_requests = 0, resends = 0, commands_answered = 0;
  int local_positions_sent = 0;
  std::string intervals_asked;  // "ATTITUDE_QUATERNION 5000 us, ..."
};

class Emulator {
 public:
  // imu: the scenario's attitude source, whose heading frame the velocities are given in.
  Emulator(const EmulatorOptions& o, const sim::ImuSpec& imu)
      : o_(o), imu_(imu), writer_(kSystemId, kComponentId, o.v1 ? 1 : 2), record_(o.record) {
    socket_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    peer_.sin_family = AF_INET;
    peer_.sin_port = htons(static_cast<std::uint16_t>(o.port));
    inet_pton(AF_INET, "127.0.0.1", &peer_.sin_addr);
  }
  ~Emulator() { ::close(socket_); }

  std::int64_t autopilot_ns(double host) const {
    return static_cast<std::int64_t>((host - boot_) * (1.0 + o_.drift_ppm * 1e-6) * 1e9);
  }

  void fly(sim::FlightSimulator& simulator, double start) {
    boot_ = start - o_.boot_age;
    start_ = start;
    const double t0 = simulator.start_time();
    ImuSample sample;
    int index = 0;
    while (!stop_signal && simulator.next_imu(sample) && sample.stamp - t0 <= o_.duration) {
      listen_until(start + (sample.stamp - t0));
      send_sample(sample, sample.stamp - t0, index);
      if (o_.local_position) send_local_position(simulator, sample.stamp, sample.stamp - t0, index);
      ++index;
    }
    listen_until(host_now() + o_.linger);
  }

  const Tally& tally() const { return tally_; }

 private:
  // Whether message `id` goes out with the sample at flight time `t`.
  bool due(MessageId id, double t, int index) {
    if (!o_.streams_on_request) return id != kAttitude || index % 20 == 0;
    Stream& stream = streams_[id];
    if (stream.interval <= 0 || t + 1e-6 < stream.next_due) return false;
    stream.next_due += stream.interval;
    if (stream.next_due <= t) stream.next_due = t + stream.interval;
    return true;
  }

  void send_sample(const ImuSample& sample, double t, int index) {
    const double now = host_now();
    const std::int64_t ns = autopilot_ns(now);
    std::vector<std::uint8_t> datagram;
    if (o_.garbage_every > 0 && index % o_.garbage_every == o_.garbage_every - 1) {
      for (int i = 0; i < 16; ++i) datagram.push_back(static_cast<std::uint8_t>(random_()));
      ++tally_.garbage_bursts;
    }
    if (index % 200 == 0) {
      Heartbeat heartbeat;
      heartbeat.type = 2;        // MAV_TYPE_QUADROTOR
      heartbeat.autopilot = 12;  // MAV_AUTOPILOT_PX4
      heartbeat.system_status = kMavStateActive;
      append(datagram, frame(kHeartbeat, encode(heartbeat)));
      const auto boot_ms = static_cast<std::uint32_t>(ns / 1'000'000);
      append(datagram, frame(kSystemTime, encode(SystemTime{0, boot_ms})));
    }
    const Eigen::Quaterniond q = ned_frd_from_enu_flu(sample.orientation);
    const Eigen::Vector3d rates = frd_from_flu(sample.angular_velocity);
    const Eigen::Vector3d acc = frd_from_flu(sample.linear_acceleration);
    HighresImu imu;
    imu.time_usec = static_cast<std::uint64_t>(ns / 1000);
    imu.xacc = static_cast<float>(acc.x());
    imu.yacc = static_cast<float>(acc.y());
    imu.zacc = static_cast<float>(acc.z());
    imu.xgyro = static_cast<float>(rates.x());
    imu.ygyro = static_cast<float>(rates.y());
    imu.zgyro = static_cast<float>(rates.z());
    imu.fields_updated = 0x3F;
    if (due(kHighresImu, t, index)) {
      append(datagram, frame(kHighresImu, encode(imu)));
      ++tally_.highres_imu_sent;
    }
    AttitudeQuaternion attitude;
    attitude.time_boot_ms = static_cast<std::uint32_t>(ns / 1'000'000);
    attitude.q1 = static_cast<float>(q.w());
    attitude.q2 = static_cast<float>(q.x());
    attitude.q3 = static_cast<float>(q.y());
    attitude.q4 = static_cast<float>(q.z());
    attitude.rollspeed = static_cast<float>(rates.x());
    attitude.pitchspeed = static_cast<float>(rates.y());
    attitude.yawspeed = static_cast<float>(rates.z());
    if (due(kAttitudeQuaternion, t, index)) append_attitude(datagram, attitude, index);
    if (due(kAttitude, t, index)) {
      const EulerAngles e = euler_zyx(q);
      Attitude euler;
      euler.time_boot_ms = attitude.time_boot_ms;
      euler.roll = static_cast<float>(e.roll);
      euler.pitch = static_cast<float>(e.pitch);
      euler.yaw = static_cast<float>(e.yaw);
      append(datagram, frame(kAttitude, encode(euler)));
    }
    if (!datagram.empty()) send(datagram);
  }

  // Whether LOCAL_POSITION_NED goes out with the sample: every 10th (20 Hz at 200 Hz), or as asked.
  bool local_position_due(double t, int index) {
    if (!o_.streams_on_request) return index % 10 == 0;
    return due(kLocalPositionNed, t, index);
  }

  void send_local_position(const sim::FlightSimulator& simulator, double stamp, double t,
                           int index) {
    if (!local_position_due(t, index)) return;
    const Eigen::Quaterniond drift = sim::heading_drift_at(imu_, simulator.trajectory(), stamp);
    const Eigen::Vector3d position =
        ned_from_enu(drift * simulator.ground_truth_at(stamp).position);
    const Eigen::Vector3d velocity =
        ned_from_enu(drift * simulator.trajectory().velocity_at(stamp));
    LocalPositionNed local;
    local.time_boot_ms = static_cast<std::uint32_t>(autopilot_ns(host_now()) / 1'000'000);
    local.x = static_cast<float>(position.x());
    local.y = static_cast<float>(position.y());
    local.z = static_cast<float>(position.z());
    local.vx = static_cast<float>(velocity.x());
    local.vy = static_cast<float>(velocity.y());
    local.vz = static_cast<float>(velocity.z());
    send(frame(kLocalPositionNed, encode(local)));
    ++tally_.local_positions_sent;
  }

  void append_attitude(std::vector<std::uint8_t>& datagram, const AttitudeQuaternion& attitude,
                       int index) {
    std::vector<std::uint8_t> attitude_frame = frame(kAttitudeQuaternion, encode(attitude));
    ++tally_.attitude_sent;
    if (o_.drop_every > 0 && index % o_.drop_every == o_.drop_every - 1) {
      ++tally_.dropped;  // numbered, never sent: a frame lost on the link
      return;
    }
    if (o_.bad_crc_every > 0 && index % o_.bad_crc_every == o_.bad_crc_every - 1) {
      attitude_frame[o_.v1 ? kHeaderV1 : kHeaderV2] ^= 0x01;  // a payload bit flipped
      ++tally_.corrupted;
    }
    append(datagram, attitude_frame);
  }

  std::vector<std::uint8_t> frame(MessageId id, const std::vector<std::uint8_t>& payload) {
    if (!o_.sign) return writer_.frame(id, payload);
    Signature signature;
    signature.link_id = 1;
    signature.timestamp = static_cast<std::uint64_t>(host_now() * 1e5);
    return writer_.frame(id, payload, signature);
  }

  static void append(std::vector<std::uint8_t>& to, const std::vector<std::uint8_t>& more) {
    to.insert(to.end(), more.begin(), more.end());
  }

  void send(const std::vector<std::uint8_t>& bytes) {
    ::sendto(socket_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&peer_),
             sizeof(peer_));
  }

  // Handles what the companion sends until host time `until`.
  void listen_until(double until) {
    std::uint8_t buffer[2048];
    for (double now = host_now(); now < until && !stop_signal; now = host_now()) {
      pollfd ready{socket_, POLLIN, 0};
      const int wait_ms = static_cast<int>(std::ceil((until - now) * 1e3));
      if (::poll(&ready, 1, wait_ms) <= 0) continue;
      const ssize_t got = ::recv(socket_, buffer, sizeof(buffer), 0);
      if (got <= 0) continue;
      reader_.feed(buffer, static_cast<std::size_t>(got), [this](const Frame& f) { handle(f); });
    }
  }

  void handle(const Frame& f) {
    if (f.message_id == kHeartbeat) {
      ++tally_.heartbeats_heard;
    } else if (f.message_id == kTimesync) {
      const Timesync request = decode_timesync(f.payload);
      if (request.tc1 != 0) return;
      send(frame(kTimesync, encode(Timesync{autopilot_ns(host_now()), request.ts1, f.system_id,
                                            f.component_id})));
      ++tally_.timesync_answered;
    } else if (f.message_id == kCommandLong) {
      handle_command(f, decode_command_long(f.payload));
    } else if (f.message_id == kVisionPositionEstimate) {
      const VisionPositionEstimate v = decode_vision_position_estimate(f.payload);
      record_ << std::setprecision(9) << "vision " << v.usec << ' ' << v.x << ' ' << v.y << ' '
              << v.z << ' ' << v.roll << ' ' << v.pitch << ' ' << v.yaw << ' '
              << int{v.reset_counter} << ' ' << v.covariance[0] << ' ' << v.covariance[6] << ' '
              << v.covariance[20] << std::endl;
      ++tally_.poses;
    } else if (f.message_id == kOdometry) {
      const Odometry m = decode_odometry(f.payload);
      record_ << std::setprecision(9) << "odometry " << m.time_usec << ' ' << m.x << ' ' << m.y
              << ' ' << m.z << ' ' << m.q[0] << ' ' << m.q[1] << ' ' << m.q[2] << ' ' << m.q[3]
              << ' ' << int{m.reset_counter} << ' ' << int{m.quality} << ' ' << int{m.frame_id}
              << ' ' << int{m.child_frame_id} << std::endl;
      ++tally_.poses;
    }
  }

  void handle_command(const Frame& f, const CommandLong& command) {
    if (command.target_system != kSystemId ||
        (command.target_component != kComponentId && command.target_component != 0)) {
      return;
    }
    CommandAck ack;
    ack.command = command.command;
    ack.result = kMavResultUnsupported;
    ack.target_system = f.system_id;
    ack.target_component = f.component_id;
    if (command.command == kMavCmdSetMessageInterval) ack.result = set_interval(command);
    if (o_.ignore_commands) return;
    send(frame(kCommandAck, encode(ack)));
    ++tally_.commands_answered;
  }

  std::uint8_t set_interval(const CommandLong& command) {
    ++tally_.interval_requests;
    if (command.confirmation > 0) ++tally_.resends;
    const auto id = static_cast<std::uint32_t>(command.param1);
    const MessageDefinition* message = find_definition(id);
    std::ostringstream asked;
    asked << (tally_.intervals_asked.empty() ? "" : ", ")
          << (message ? message->name() : std::to_string(id)) << ' ' << command.param2 << " us";
    tally_.intervals_asked += asked.str();
    if (!streamable(id) || o_.refuse_intervals) return kMavResultDenied;
    if (o_.ignore_commands || !o_.streams_on_request) return kMavResultAccepted;
    // -1: stop; 0: the default, which on this port is nothing.
    const double interval = command.param2 > 0 ? command.param2 * 1e-6 : 0.0;
    streams_[static_cast<MessageId>(id)] = Stream{interval, host_now() - start_};
    return kMavResultAccepted;
  }

  EmulatorOptions o_;
  sim::ImuSpec imu_;
  FrameWriter writer_;
  FrameReader reader_;
  std::ofstream record_;
  int socket_ = -1;
  sockaddr_in peer_{};
  double boot_ = 0;
  double start_ = 0;  // host time of the flight's start
  std::map<MessageId, Stream> streams_;
  std::mt19937 random_{11};
  Tally tally_;
};

}  // namespace
}  // namespace uavslam::mavlink

int main(int argc, char** argv) {
  using uavslam::mavlink::EmulatorOptions;
  CLI::App app{
      "autopilot_emulator: a PX4-like autopilot streaming a simulated flight over "
      "MAVLink to 127.0.0.1:PORT (imu_bridge's tests)"};
  EmulatorOptions o;
  app.add_option("--port", o.port, "the companion's UDP port on 127.0.0.1")->required();
  app.add_option("--scenario", o.scenario, "scenario YAML")->capture_default_str();
  app.add_option("--duration", o.duration, "s of the flight to send")->capture_default_str();
  app.add_option("--start-at", o.start_at, "host time (s since 1970) of the first sample");
  app.add_option("--boot-age", o.boot_age, "s since the autopilot's boot at the flight's start")
      ->capture_default_str();
  app.add_option("--drift-ppm", o.drift_ppm, "the autopilot clock's rate error")
      ->capture_default_str();
  app.add_option("--linger", o.linger, "s to keep listening after the flight")
      ->capture_default_str();
  app.add_flag("--v1", o.v1, "send MAVLink 1 frames");
  app.add_flag("--signed", o.sign, "send signed MAVLink 2 frames");
  app.add_option("--bad-crc-every", o.bad_crc_every, "corrupt every Nth attitude frame");
  app.add_option("--garbage-every", o.garbage_every, "16 garbage bytes before every Nth sample");
  app.add_option("--drop-every", o.drop_every, "lose every Nth attitude frame");
  app.add_flag("--streams-on-request", o.streams_on_request,
               "send only HEARTBEAT and SYSTEM_TIME until a message is asked for with "
               "MAV_CMD_SET_MESSAGE_INTERVAL");
  app.add_flag("--refuse-intervals", o.refuse_intervals,
               "answer MAV_CMD_SET_MESSAGE_INTERVAL with MAV_RESULT_DENIED");
  app.add_flag("--ignore-commands", o.ignore_commands, "answer no COMMAND_LONG");
  app.add_flag("--local-position", o.local_position,
               "also send LOCAL_POSITION_NED (the true velocity) every 10th IMU sample");
  app.add_option("--record", o.record, "file for the poses received")->required();
  CLI11_PARSE(app, argc, argv);
  std::signal(SIGINT, uavslam::mavlink::request_stop);
  std::signal(SIGTERM, uavslam::mavlink::request_stop);
  try {
    const uavslam::sim::Scenario scenario = uavslam::io::load_scenario(o.scenario);
    uavslam::sim::FlightSimulator simulator(scenario);
    uavslam::mavlink::Emulator emulator(o, scenario.imu);
    const double start = o.start_at > 0 ? o.start_at : uavslam::mavlink::host_now() + 0.5;
    emulator.fly(simulator, start);
    const auto& t = emulator.tally();
    std::cout << "autopilot_emulator: sent " << t.attitude_sent << " attitude samples ("
              << t.dropped << " dropped, " << t.corrupted << " corrupted), " << t.garbage_bursts
              << " garbage bursts, answered " << t.timesync_answered << " timesync requests, heard "
              << t.heartbeats_heard << " heartbeats, recorded " << t.poses << " poses, sent "
              << t.highres_imu_sent << " HIGHRES_IMU, received " << t.interval_requests
              << " SET_MESSAGE_INTERVAL (" << t.resends << " resends; "
              << (t.intervals_asked.empty() ? "none" : t.intervals_asked) << "), answered "
              << t.commands_answered << " commands, sent " << t.local_positions_sent
              << " LOCAL_POSITION_NED" << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "autopilot_emulator: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
