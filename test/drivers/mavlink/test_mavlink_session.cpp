// AutopilotSession asking the autopilot for its streams (MAV_CMD_SET_MESSAGE_INTERVAL in
// COMMAND_LONG, answered by COMMAND_ACK; mavlink.io's command protocol), bytes in and bytes out
// with the time given: the exact frame of one request, resends with the confirmation counting up
// until an answer or giving up, refusals not retried, requests again after the autopilot reboots.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drivers/mavlink/AutopilotSession.hpp"
#include "drivers/mavlink/CommonMessages.hpp"
#include "drivers/mavlink/Crc.hpp"
#include "drivers/mavlink/FrameReader.hpp"
#include "drivers/mavlink/FrameWriter.hpp"
#include "drivers/mavlink/Messages.hpp"

namespace uavslam::mavlink {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr std::uint8_t kAutopilotSystem = 42;
constexpr std::uint8_t kAutopilotComponent = 1;
constexpr std::uint8_t kOurComponent = kMavCompIdVisualInertialOdometry;

Bytes px4_heartbeat(FrameWriter& autopilot) {
  Heartbeat heartbeat;
  heartbeat.type = 2;        // MAV_TYPE_QUADROTOR
  heartbeat.autopilot = 12;  // MAV_AUTOPILOT_PX4
  heartbeat.system_status = kMavStateActive;
  return autopilot.frame(kHeartbeat, encode(heartbeat));
}

// The session on one side, an autopilot writing frames on the other; what the session sends is
// kept whole (`sent`) and read back into frames (`frames`).
class SessionLink {
 public:
  explicit SessionLink(double attitude_rate = 200.0, double imu_rate = 200.0)
      : session_(options(attitude_rate, imu_rate)) {}

  static SessionOptions options(double attitude_rate, double imu_rate) {
    SessionOptions o;
    o.attitude_rate = attitude_rate;
    o.imu_rate = imu_rate;
    return o;
  }

  void heartbeat(double now) { deliver(px4_heartbeat(autopilot_), now); }
  void ack(std::uint8_t result, double now, std::uint8_t target_component = kOurComponent) {
    CommandAck ack;
    ack.command = kMavCmdSetMessageInterval;
    ack.result = result;
    ack.target_system = kAutopilotSystem;
    ack.target_component = target_component;
    deliver(autopilot_.frame(kCommandAck, encode(ack)), now);
  }
  void deliver(const Bytes& bytes, double now) {
    session_.receive(
        bytes.data(), bytes.size(), now, [](const ImuSample&) {}, keep());
  }
  void tick(double now) { session_.tick(now, keep()); }

  // The SET_MESSAGE_INTERVAL commands sent since the last call.
  std::vector<CommandLong> commands() {
    std::vector<CommandLong> found;
    for (; read_ < frames_.size(); ++read_) {
      if (frames_[read_].message_id == kCommandLong) {
        found.push_back(decode_command_long(frames_[read_].payload));
      }
    }
    return found;
  }

  AutopilotSession& session() { return session_; }
  FrameWriter& autopilot() { return autopilot_; }
  const std::vector<Bytes>& sent() const { return sent_; }
  const std::vector<Frame>& frames() const { return frames_; }

 private:
  AutopilotSession::Send keep() {
    return [this](const Bytes& bytes) {
      sent_.push_back(bytes);
      reader_.feed(bytes.data(), bytes.size(), [this](const Frame& f) { frames_.push_back(f); });
    };
  }

  AutopilotSession session_;
  FrameWriter autopilot_{kAutopilotSystem, kAutopilotComponent};
  FrameReader reader_;
  std::vector<Bytes> sent_;
  std::vector<Frame> frames_;
  std::size_t read_ = 0;
};

bool mentions(const std::vector<std::string>& lines, const std::string& a, const std::string& b) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& line) {
    return line.find(a) != std::string::npos && line.find(b) != std::string::npos;
  });
}

TEST(MavlinkStreamRequests, AskForNothingBeforeTheAutopilotIsHeard) {
  SessionLink link;
  link.tick(0.0);
  link.tick(5.0);
  EXPECT_TRUE(link.commands().empty());
}

TEST(MavlinkStreamRequests, TheRequestFrameByteByByte) {
  SessionLink link(200.0, 0.0);  // ATTITUDE_QUATERNION only
  link.heartbeat(0.0);
  link.tick(0.0);  // our HEARTBEAT (sequence 0), TIMESYNC request (1), the command (2)
  const auto command = std::find_if(link.frames().begin(), link.frames().end(),
                                    [](const Frame& f) { return f.message_id == kCommandLong; });
  ASSERT_NE(command, link.frames().end());
  const Bytes& sent = link.sent()[static_cast<std::size_t>(command - link.frames().begin())];
  // MAVLink 2: the vehicle's system id (taken from its heartbeat), our component, message 76. The
  // payload by field size: param1..param7 (float), command (uint16), target_system,
  // target_component, confirmation (uint8); the trailing zero (confirmation 0) is truncated.
  Bytes expected = {0xFD, 32,   0,    0,    2,    kAutopilotSystem, kOurComponent, 76, 0,
                    0,    0x00, 0x00, 0xF8, 0x41,  // param1 = 31.0f: ATTITUDE_QUATERNION
                    0x00, 0x40, 0x9C, 0x45};       // param2 = 5000.0f: 5000 us, 200 Hz
  expected.insert(expected.end(), 20, 0);          // param3..param7
  const Bytes tail = {0xFF, 0x01,                  // command 511, little-endian
                      kAutopilotSystem, kAutopilotComponent};
  expected.insert(expected.end(), tail.begin(), tail.end());
  std::uint16_t crc = crc_accumulate(expected.data() + 1, expected.size() - 1, kCrcInit);
  crc = crc_accumulate(std::uint8_t{152}, crc);  // COMMAND_LONG's published CRC_EXTRA
  expected.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  expected.push_back(static_cast<std::uint8_t>(crc >> 8));
  EXPECT_EQ(sent, expected);
  EXPECT_EQ(link.session().counts().interval_requests.sent, 1u);
}

TEST(MavlinkStreamRequests, ResendWithoutAnAckThenGiveUp) {
  SessionLink link(200.0, 0.0);
  link.heartbeat(0.0);
  link.tick(0.0);
  std::vector<CommandLong> sent = link.commands();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].confirmation, 0);
  link.tick(0.9);
  EXPECT_TRUE(link.commands().empty());  // still waiting
  link.tick(1.0);
  sent = link.commands();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].confirmation, 1);
  EXPECT_EQ(sent[0].param1, 31.0f);
  link.tick(2.0);
  sent = link.commands();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].confirmation, 2);
  EXPECT_TRUE(link.session().take_reports().empty());
  link.tick(3.0);
  link.tick(10.0);
  EXPECT_TRUE(link.commands().empty());  // three tries, then given up
  const IntervalRequestCounts& counts = link.session().counts().interval_requests;
  EXPECT_EQ(counts.sent, 3u);
  EXPECT_EQ(counts.unanswered, 1u);
  EXPECT_EQ(counts.accepted, 0u);
  const std::vector<std::string> reports = link.session().take_reports();
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_TRUE(mentions(reports, "ATTITUDE_QUATERNION", "unanswered")) << reports[0];
  EXPECT_TRUE(link.session().take_reports().empty());  // reported once
}

TEST(MavlinkStreamRequests, AcceptedStopsResendsAndTheNextMessageFollows) {
  SessionLink link;
  link.heartbeat(0.0);
  link.tick(0.0);
  std::vector<CommandLong> sent = link.commands();
  ASSERT_EQ(sent.size(), 1u);  // one command in flight at a time
  EXPECT_EQ(sent[0].param1, 31.0f);
  link.ack(kMavResultAccepted, 0.1);
  link.tick(0.1);
  sent = link.commands();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].param1, 105.0f);  // HIGHRES_IMU
  EXPECT_EQ(sent[0].param2, 5000.0f);
  EXPECT_EQ(sent[0].confirmation, 0);
  link.ack(kMavResultAccepted, 0.2);
  for (double t = 0.2; t < 10.0; t += 0.5) link.tick(t);
  EXPECT_TRUE(link.commands().empty());
  const IntervalRequestCounts& counts = link.session().counts().interval_requests;
  EXPECT_EQ(counts.sent, 2u);
  EXPECT_EQ(counts.accepted, 2u);
  const std::vector<std::string> reports = link.session().take_reports();
  EXPECT_TRUE(mentions(reports, "ATTITUDE_QUATERNION", "accepted"));
  EXPECT_TRUE(mentions(reports, "HIGHRES_IMU", "accepted"));
}

TEST(MavlinkStreamRequests, AnAckForSomeoneElseIsNotOurs) {
  SessionLink link(200.0, 0.0);
  link.heartbeat(0.0);
  link.tick(0.0);
  ASSERT_EQ(link.commands().size(), 1u);
  link.ack(kMavResultAccepted, 0.1, 190);  // to another component of our system
  link.tick(1.0);
  const std::vector<CommandLong> sent = link.commands();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].confirmation, 1);
  EXPECT_EQ(link.session().counts().interval_requests.accepted, 0u);
}

TEST(MavlinkStreamRequests, DeniedIsCountedReportedAndNotRetried) {
  SessionLink link;
  link.heartbeat(0.0);
  link.tick(0.0);
  ASSERT_EQ(link.commands().size(), 1u);
  link.ack(kMavResultDenied, 0.1);
  link.tick(0.1);
  std::vector<CommandLong> sent = link.commands();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].param1, 105.0f);  // on to the next message
  link.ack(kMavResultUnsupported, 0.2);
  for (double t = 0.2; t < 10.0; t += 0.5) link.tick(t);
  EXPECT_TRUE(link.commands().empty());
  const IntervalRequestCounts& counts = link.session().counts().interval_requests;
  EXPECT_EQ(counts.sent, 2u);
  EXPECT_EQ(counts.refused, 2u);
  const std::vector<std::string> reports = link.session().take_reports();
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_TRUE(mentions(reports, "ATTITUDE_QUATERNION", "MAV_RESULT_DENIED"));
  EXPECT_TRUE(mentions(reports, "HIGHRES_IMU", "MAV_RESULT_UNSUPPORTED"));
}

TEST(MavlinkStreamRequests, TemporarilyRejectedIsAskedAgainAfterTheTimeout) {
  SessionLink link(200.0, 0.0);
  link.heartbeat(0.0);
  link.tick(0.0);
  ASSERT_EQ(link.commands().size(), 1u);
  link.ack(kMavResultTemporarilyRejected, 0.1);
  link.tick(0.5);
  EXPECT_TRUE(link.commands().empty());
  link.tick(1.0);
  const std::vector<CommandLong> sent = link.commands();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].confirmation, 1);
  link.ack(kMavResultAccepted, 1.1);
  EXPECT_EQ(link.session().counts().interval_requests.accepted, 1u);
}

TEST(MavlinkStreamRequests, AskedAgainWhenTheAutopilotReboots) {
  SessionLink link;
  link.heartbeat(0.0);
  link.tick(0.0);
  link.ack(kMavResultAccepted, 0.1);
  link.tick(0.1);
  link.ack(kMavResultAccepted, 0.2);
  for (double t = 1.0; t <= 4.0; t += 1.0) {  // heartbeats once a second: the same boot
    link.heartbeat(t);
    link.tick(t);
  }
  EXPECT_EQ(link.commands().size(), 2u);
  link.heartbeat(7.5);  // 3.5 s of silence: it rebooted
  link.tick(7.5);
  std::vector<CommandLong> sent = link.commands();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].param1, 31.0f);
  EXPECT_EQ(sent[0].confirmation, 0);
  EXPECT_EQ(link.session().counts().reboots, 1u);
  link.ack(kMavResultAccepted, 7.6);
  link.tick(7.6);
  ASSERT_EQ(link.commands().size(), 1u);
  link.ack(kMavResultAccepted, 7.7);
  EXPECT_EQ(link.session().counts().interval_requests.accepted, 4u);

  // A new system id (the vehicle renumbered): asked again, at the new id, from the new id.
  FrameWriter renumbered(43, kAutopilotComponent);
  link.deliver(px4_heartbeat(renumbered), 8.0);
  link.tick(8.0);
  sent = link.commands();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].target_system, 43);
  EXPECT_EQ(link.frames().back().system_id, 43);
  EXPECT_EQ(link.session().counts().reboots, 2u);
}

TEST(MavlinkStreamRequests, ZeroRatesAskForNothing) {
  SessionLink link(0.0, 0.0);
  link.heartbeat(0.0);
  for (double t = 0.0; t < 5.0; t += 0.5) link.tick(t);
  EXPECT_TRUE(link.commands().empty());
  EXPECT_EQ(link.session().counts().interval_requests.sent, 0u);
}

// The autopilot fuses our matches; a pose the IMU alone carried (quality 0, dead-reckoned) would
// give it its own IMU a second time.
TEST(MavlinkPoses, ADeadReckonedPoseIsWithheldFromTheAutopilot) {
  SessionLink link(0.0, 0.0);
  link.heartbeat(0.0);
  PoseEstimate estimate;
  estimate.pose.stamp = 1.0;
  estimate.quality = 0.8f;
  link.session().send_pose(estimate, [&](const Bytes& bytes) { link.deliver(bytes, 1.0); });
  estimate.quality = 0.0f;
  estimate.pose.stamp = 1.1;
  std::size_t sent = 0;
  link.session().send_pose(estimate, [&](const Bytes&) { ++sent; });
  EXPECT_EQ(sent, 0u);
  EXPECT_EQ(link.session().counts().poses_sent, 1u);
  EXPECT_EQ(link.session().counts().poses_withheld, 1u);
}

// LOCAL_POSITION_NED's velocity, in NED, becomes a VelocitySample in ENU stated to the
// configured sigma, and its stream is asked for; without a sigma the message is not read and
// not asked for (an autopilot whose velocity comes from our own poses must not feed them back).
TEST(MavlinkVelocity, TheAutopilotsVelocityIsReadInOurFramesOnlyWhenAsked) {
  LocalPositionNed local;
  local.time_boot_ms = 1000;
  local.vx = 1.0f;   // north
  local.vy = 2.0f;   // east
  local.vz = -0.5f;  // up
  for (const double sigma : {0.0, 0.05}) {
    SessionOptions options = SessionLink::options(0.0, 0.0);
    options.velocity_sigma = sigma;
    options.velocity_rate = 25.0;
    AutopilotSession session(options);
    FrameWriter autopilot(kAutopilotSystem, kAutopilotComponent);
    std::vector<VelocitySample> velocities;
    std::vector<Frame> sent;
    FrameReader reader;
    const AutopilotSession::Send keep = [&](const Bytes& bytes) {
      reader.feed(bytes.data(), bytes.size(), [&](const Frame& f) { sent.push_back(f); });
    };
    const auto deliver = [&](const Bytes& bytes, double now) {
      session.receive(
          bytes.data(), bytes.size(), now, [](const ImuSample&) {}, keep,
          [&](const VelocitySample& v) { velocities.push_back(v); });
    };
    deliver(px4_heartbeat(autopilot), 0.0);
    session.tick(0.0, keep);
    deliver(autopilot.frame(kLocalPositionNed, encode(local)), 1.0);
    std::vector<CommandLong> asked;
    for (const Frame& f : sent) {
      if (f.message_id == kCommandLong) asked.push_back(decode_command_long(f.payload));
    }
    if (sigma == 0.0) {
      EXPECT_TRUE(velocities.empty());
      EXPECT_TRUE(asked.empty());
      continue;
    }
    ASSERT_EQ(asked.size(), 1u);
    EXPECT_EQ(asked[0].param1, static_cast<float>(kLocalPositionNed));
    EXPECT_EQ(asked[0].param2, 40000.0f);  // us: 25 Hz
    ASSERT_EQ(velocities.size(), 1u);
    EXPECT_TRUE(velocities[0].velocity.isApprox(Vec3(2.0, 1.0, 0.5))) << velocities[0].velocity;
    EXPECT_TRUE(velocities[0].covariance.isApprox(0.0025 * Eigen::Matrix3d::Identity()));
    EXPECT_EQ(velocities[0].stamp, 1.0) << "stamped on arrival until the clocks are synchronised";
    EXPECT_EQ(session.counts().velocity_samples, 1u);
  }
}

TEST(MavlinkStreamRequests, AGroundStationHeartbeatIsNotTheAutopilot) {
  SessionLink link;
  FrameWriter ground_station(255, 190);
  Heartbeat heartbeat;
  heartbeat.type = 6;  // MAV_TYPE_GCS
  heartbeat.autopilot = kMavAutopilotInvalid;
  link.deliver(ground_station.frame(kHeartbeat, encode(heartbeat)), 0.0);
  link.tick(0.0);
  EXPECT_FALSE(link.session().autopilot_heard());
  EXPECT_TRUE(link.commands().empty());
}

TEST(MavlinkStreamRequests, ACommandToUsIsAnsweredUnsupported) {
  SessionLink link(0.0, 0.0);
  link.heartbeat(0.0);
  CommandLong command;
  command.target_system = kAutopilotSystem;
  command.target_component = kOurComponent;
  command.command = 520;  // MAV_CMD_REQUEST_AUTOPILOT_CAPABILITIES
  link.deliver(link.autopilot().frame(kCommandLong, encode(command)), 0.1);
  ASSERT_FALSE(link.frames().empty());
  const Frame& answer = link.frames().back();
  ASSERT_EQ(answer.message_id, static_cast<std::uint32_t>(kCommandAck));
  const CommandAck ack = decode_command_ack(answer.payload);
  EXPECT_EQ(ack.command, 520);
  EXPECT_EQ(ack.result, kMavResultUnsupported);
  EXPECT_EQ(ack.target_system, kAutopilotSystem);
  EXPECT_EQ(ack.target_component, kAutopilotComponent);
}

}  // namespace
}  // namespace uavslam::mavlink
