// imu_bridge against the emulated autopilot (autopilot_emulator) over UDP on 127.0.0.1: the `imu`
// samples it publishes are the simulator's, converted from NED/FRD back to our frames, one per
// attitude the emulator sent; faults (signed frames, bad checksums, garbage, lost frames) are
// counted while the stream goes on; `pose` samples come out at the autopilot as
// VISION_POSITION_ESTIMATE / ODOMETRY in NED; and from an autopilot that streams only what it is
// asked for, samples arrive at the rate imu_bridge asked for (MAV_CMD_SET_MESSAGE_INTERVAL), or
// none when it was told to ask for nothing.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <msg/ImuPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <msg/TwistPubSubTypes.h>

#include "ProcessTest.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "io/ScenarioFile.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam::test {
namespace {

using namespace std::chrono_literals;
using process::ChildProcess;

const std::string kScenario = std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/short.yaml";
constexpr double kImuRate = 200.0;  // short.yaml's imu.rate_hz

double host_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// The number after `label` in the last line of `log` that has it ("601 attitude samples").
long count_in(const std::string& log, const std::string& label) {
  const std::regex pattern("([0-9]+) " + label);
  long value = -1;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), pattern);
       it != std::sregex_iterator(); ++it) {
    value = std::stol((*it)[1]);
  }
  return value;
}

struct ImuRun {
  std::vector<ImuSample> received;
  std::string emulator_log;
  std::string bridge_log;
  int bridge_exit = -1;
};

class ImuBridgeMavlinkTest : public ProcessTest {
 protected:
  // imu_bridge on `port` (with `bridge_flags`), the test reading its `imu`, and the emulator
  // (emulator_argv) flying from `start` for `duration` s; both stopped, their logs kept.
  ImuRun run_imu(int domain, int port, double start, double duration,
                 const std::vector<std::string>& emulator_argv,
                 const std::vector<std::string>& bridge_flags = {});
  std::vector<std::string> poses_at_autopilot(
      dds::Writer<msg::PoseWithCovarianceStampedPubSubType>& poses, int domain, int port,
      const std::vector<std::string>& bridge_flags);

  std::vector<std::string> emulator_argv(int port, double duration,
                                         const std::vector<std::string>& extra) const {
    std::vector<std::string> argv{binary("autopilot_emulator"),
                                  "--port",
                                  std::to_string(port),
                                  "--scenario",
                                  kScenario,
                                  "--duration",
                                  std::to_string(duration),
                                  "--record",
                                  path("poses.txt")};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return argv;
  }

  std::vector<std::string> record() const {
    std::ifstream in(path("poses.txt"));
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }
};

// The simulator's IMU samples of the first `duration` s (what the emulator sends).
std::vector<ImuSample> simulated_imu(double duration) {
  sim::FlightSimulator simulator(io::load_scenario(kScenario));
  std::vector<ImuSample> samples;
  ImuSample sample;
  while (simulator.next_imu(sample) && sample.stamp - simulator.start_time() <= duration + 1.0) {
    samples.push_back(sample);
  }
  return samples;
}

// The smallest angle between `q` and the simulated orientations near index `guess`.
double closest_angle(const std::vector<ImuSample>& truth, const Eigen::Quaterniond& q, long guess,
                     std::size_t& best) {
  double smallest = 1e9;
  for (long i = std::max(0L, guess - 40); i < std::min(static_cast<long>(truth.size()), guess + 40);
       ++i) {
    const double angle = truth[static_cast<std::size_t>(i)].orientation.angularDistance(q);
    if (angle < smallest) {
      smallest = angle;
      best = static_cast<std::size_t>(i);
    }
  }
  return smallest;
}

ImuRun ImuBridgeMavlinkTest::run_imu(int domain, int port, double start, double duration,
                                     const std::vector<std::string>& emulator_argv,
                                     const std::vector<std::string>& bridge_flags) {
  ImuRun run;
  dds::Participant participant(domain, dds::default_profiles_path(), "uavslam_loopback", "test");
  std::mutex mutex;
  dds::Reader<msg::ImuPubSubType> reader(participant, dds::topic_name("uav1", dds::kImuTopic),
                                         "sensor_reader",
                                         [&](const msg::Imu& message, const auto&) {
                                           const std::lock_guard<std::mutex> lock(mutex);
                                           run.received.push_back(dds::from_msg(message));
                                         });
  std::vector<std::string> flags{"--source", "mavlink:udp:" + std::to_string(port),
                                 "--mavlink-status-period", "1"};
  flags.insert(flags.end(), bridge_flags.begin(), bridge_flags.end());
  ChildProcess bridge(node_argv("imu_bridge", domain, flags), log_path("imu_bridge"));
  EXPECT_TRUE(reader.wait_for_matched(1, 30s)) << bridge.log();
  std::vector<std::string> argv = emulator_argv;
  argv.insert(argv.end(), {"--start-at", std::to_string(start)});
  ChildProcess emulator(argv, log_path("emulator"));
  EXPECT_TRUE(emulator.wait(std::chrono::seconds(static_cast<int>(duration) + 60)));
  EXPECT_EQ(emulator.exit_code(), 0) << emulator.log();
  run.emulator_log = emulator.log();
  const long sent = count_in(run.emulator_log, "attitude samples");
  reader.wait_for_received(static_cast<std::size_t>(std::max(sent, 0L)), 10s);
  run.bridge_exit = bridge.stop(10s);
  run.bridge_log = bridge.log();
  const std::lock_guard<std::mutex> lock(mutex);
  return run;
}

TEST_F(ImuBridgeMavlinkTest, PublishesTheAutopilotAttitudeInOurFrames) {
  constexpr int kDomain = 197;
  constexpr int kPort = 24551;
  constexpr double kDuration = 3.0;
  const double start = host_now() + 1.0;
  const ImuRun run = run_imu(kDomain, kPort, start, kDuration,
                             emulator_argv(kPort, kDuration, {"--drift-ppm", "50"}));
  ASSERT_EQ(run.bridge_exit, 0) << run.bridge_log;
  const long sent = count_in(run.emulator_log, "attitude samples");
  ASSERT_GT(sent, 500) << run.emulator_log;  // 3 s at 200 Hz
  EXPECT_EQ(static_cast<long>(run.received.size()), sent) << run.bridge_log;
  EXPECT_EQ(count_in(run.bridge_log, "CRC errors"), 0) << run.bridge_log;
  EXPECT_EQ(count_in(run.bridge_log, "sequence gaps"), 0) << run.bridge_log;
  EXPECT_GE(count_in(run.emulator_log, "timesync requests"), 2) << run.emulator_log;
  // TIMESYNC: the emulated autopilot booted 100 s before the flight (--boot-age).
  std::smatch offset;
  ASSERT_TRUE(std::regex_search(run.bridge_log, offset, std::regex("time offset ([0-9.]+) s")))
      << run.bridge_log;
  EXPECT_NEAR(std::stod(offset[1]), start - 100.0, 0.01) << run.bridge_log;
  EXPECT_GE(count_in(run.emulator_log, "heartbeats"), 2) << run.emulator_log;

  const std::vector<ImuSample> truth = simulated_imu(kDuration);
  std::vector<double> spacing;
  for (std::size_t i = 0; i < run.received.size(); ++i) {
    const ImuSample& got = run.received[i];
    const long guess = std::lround((got.stamp - start) * kImuRate);
    std::size_t best = 0;
    // float32 on the wire: a few 1e-7 rad.
    ASSERT_LT(closest_angle(truth, got.orientation, guess, best), 1e-5) << "sample " << i;
    EXPECT_LT((got.linear_acceleration - truth[best].linear_acceleration).norm(), 1e-4);
    EXPECT_LT((got.angular_velocity - truth[best].angular_velocity).norm(), 1e-5);
    if (i > 0) spacing.push_back(got.stamp - run.received[i - 1].stamp);
  }
  // Stamps: the autopilot's clock mapped to ours, at the emulator's rate.
  std::nth_element(spacing.begin(), spacing.begin() + static_cast<long>(spacing.size() / 2),
                   spacing.end());
  EXPECT_NEAR(spacing[spacing.size() / 2], 1.0 / kImuRate, 1.5e-3);
}

// An autopilot whose velocity comes from its own optical flow (the emulator's LOCAL_POSITION_NED,
// the true velocity): with --mavlink-velocity-sigma imu_bridge publishes it on `velocity`, in our
// frames (ENU) and on our clock, stated to that sigma, one per message.
TEST_F(ImuBridgeMavlinkTest, PublishesTheAutopilotsVelocityWhenAskedTo) {
  constexpr int kDomain = 223;
  constexpr int kPort = 24573;
  constexpr double kDuration = 3.0;
  dds::Participant participant(kDomain, dds::default_profiles_path(), "uavslam_loopback", "test");
  std::mutex mutex;
  std::vector<VelocitySample> velocities;
  dds::Reader<msg::TwistWithCovarianceStampedPubSubType> reader(
      participant, dds::topic_name("uav1", dds::kVelocityTopic), "sensor_reader",
      [&](const msg::TwistWithCovarianceStamped& message, const auto&) {
        const std::lock_guard<std::mutex> lock(mutex);
        velocities.push_back(dds::from_msg(message));
      });
  const double start = host_now() + 1.0;
  const ImuRun run = run_imu(kDomain, kPort, start, kDuration,
                             emulator_argv(kPort, kDuration, {"--local-position"}),
                             {"--mavlink-velocity-sigma", "0.05"});
  ASSERT_EQ(run.bridge_exit, 0) << run.bridge_log;
  const long sent = count_in(run.emulator_log, "LOCAL_POSITION_NED");
  ASSERT_GT(sent, 50) << run.emulator_log;  // 3 s at 20 Hz
  reader.wait_for_received(static_cast<std::size_t>(sent), 10s);
  const std::lock_guard<std::mutex> lock(mutex);
  EXPECT_EQ(static_cast<long>(velocities.size()), sent) << run.bridge_log;
  sim::FlightSimulator truth(io::load_scenario(kScenario));
  double worst = 0.0;
  for (const VelocitySample& v : velocities) {
    // Stamped by the autopilot's clock mapped to ours; the flight started at `start`.
    const double t = truth.start_time() + (v.stamp - start);
    worst = std::max(worst, (v.velocity - truth.trajectory().velocity_at(t)).norm());
    EXPECT_TRUE(v.covariance.isApprox(0.0025 * Eigen::Matrix3d::Identity()));
  }
  EXPECT_LT(worst, 0.02) << "a few ms of stamp error at most";
}

TEST_F(ImuBridgeMavlinkTest, CountsFaultsAndKeepsPublishing) {
  constexpr int kDomain = 198;
  constexpr int kPort = 24552;
  constexpr double kDuration = 3.0;
  const ImuRun run = run_imu(kDomain, kPort, host_now() + 1.0, kDuration,
                             emulator_argv(kPort, kDuration,
                                           {"--signed", "--bad-crc-every", "50", "--garbage-every",
                                            "40", "--drop-every", "70"}));
  ASSERT_EQ(run.bridge_exit, 0) << run.bridge_log;
  const long sent = count_in(run.emulator_log, "attitude samples");
  const long dropped = count_in(run.emulator_log, "dropped");
  const long corrupted = count_in(run.emulator_log, "corrupted");
  ASSERT_GT(dropped, 0);
  ASSERT_GT(corrupted, 0);
  // Every attitude that arrived intact became an imu sample; a false start marker in the garbage
  // may, rarely, cost one more.
  EXPECT_LE(static_cast<long>(run.received.size()), sent - dropped - corrupted);
  EXPECT_GE(static_cast<long>(run.received.size()), sent - dropped - corrupted - 2)
      << run.bridge_log;
  EXPECT_GE(count_in(run.bridge_log, "CRC errors"), corrupted) << run.bridge_log;
  EXPECT_GE(count_in(run.bridge_log, "sequence gaps"), dropped + corrupted) << run.bridge_log;
  EXPECT_GT(count_in(run.bridge_log, "garbage bytes"), 0) << run.bridge_log;
  EXPECT_GT(count_in(run.bridge_log, "signed\\)"), 0);  // "(0 v1, N signed)"
}

// The median spacing of the samples' stamps (the autopilot's clock mapped to ours), s.
double median_spacing(const std::vector<ImuSample>& samples) {
  std::vector<double> spacing;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    spacing.push_back(samples[i].stamp - samples[i - 1].stamp);
  }
  if (spacing.empty()) return 0;
  std::nth_element(spacing.begin(), spacing.begin() + static_cast<long>(spacing.size() / 2),
                   spacing.end());
  return spacing[spacing.size() / 2];
}

// An autopilot port that streams nothing by default (ArduPilot's HIGHRES_IMU, a PX4 port's
// messages it was not configured for): the samples come because imu_bridge asked, at its rate.
TEST_F(ImuBridgeMavlinkTest, StreamsArriveAtTheRateTheBridgeAskedFor) {
  constexpr int kDomain = 220;
  constexpr int kPort = 24570;
  constexpr double kDuration = 4.0;
  constexpr double kAskedRate = 50.0;  // a quarter of the emulator's 200 Hz
  const ImuRun run = run_imu(kDomain, kPort, host_now() + 1.0, kDuration,
                             emulator_argv(kPort, kDuration, {"--streams-on-request"}),
                             {"--mavlink-attitude-rate", "50", "--mavlink-imu-rate", "50"});
  ASSERT_EQ(run.bridge_exit, 0) << run.bridge_log;
  EXPECT_EQ(count_in(run.emulator_log, "SET_MESSAGE_INTERVAL"), 2) << run.emulator_log;
  EXPECT_NE(run.emulator_log.find("ATTITUDE_QUATERNION 20000 us"), std::string::npos)
      << run.emulator_log;
  EXPECT_NE(run.emulator_log.find("HIGHRES_IMU 20000 us"), std::string::npos) << run.emulator_log;
  EXPECT_EQ(count_in(run.bridge_log, "accepted"), 2) << run.bridge_log;
  // 50 Hz over the 4 s flight is 200 attitudes; 200 Hz (not asked, or ignored) would be 800.
  const long sent = count_in(run.emulator_log, "attitude samples");
  EXPECT_GE(sent, static_cast<long>(0.7 * kAskedRate * kDuration)) << run.emulator_log;
  EXPECT_LE(sent, static_cast<long>(1.1 * kAskedRate * kDuration)) << run.emulator_log;
  EXPECT_EQ(static_cast<long>(run.received.size()), sent) << run.bridge_log;
  EXPECT_NEAR(median_spacing(run.received), 1.0 / kAskedRate, 2e-3);
  ASSERT_FALSE(run.received.empty());
  // HIGHRES_IMU was asked for too: the accelerations are the simulator's, gravity included.
  EXPECT_GT(run.received.back().linear_acceleration.norm(), 5.0);
}

TEST_F(ImuBridgeMavlinkTest, RatesOfZeroAskForNothing) {
  constexpr int kDomain = 221;
  constexpr int kPort = 24571;
  constexpr double kDuration = 3.0;
  const ImuRun run = run_imu(kDomain, kPort, host_now() + 1.0, kDuration,
                             emulator_argv(kPort, kDuration, {"--streams-on-request"}),
                             {"--mavlink-attitude-rate", "0", "--mavlink-imu-rate", "0"});
  ASSERT_EQ(run.bridge_exit, 0) << run.bridge_log;
  // The bridge heard the autopilot (it only sends TIMESYNC requests then) and asked for nothing.
  EXPECT_GE(count_in(run.emulator_log, "timesync requests"), 1) << run.emulator_log;
  EXPECT_EQ(count_in(run.emulator_log, "SET_MESSAGE_INTERVAL"), 0) << run.emulator_log;
  EXPECT_EQ(count_in(run.emulator_log, "attitude samples"), 0) << run.emulator_log;
  EXPECT_EQ(count_in(run.bridge_log, "stream requests"), 0) << run.bridge_log;
  EXPECT_TRUE(run.received.empty());
}

TEST_F(ImuBridgeMavlinkTest, RefusedStreamsAreReported) {
  constexpr int kDomain = 222;
  constexpr int kPort = 24572;
  constexpr double kDuration = 3.0;
  const ImuRun run =
      run_imu(kDomain, kPort, host_now() + 1.0, kDuration,
              emulator_argv(kPort, kDuration, {"--streams-on-request", "--refuse-intervals"}));
  ASSERT_EQ(run.bridge_exit, 0) << run.bridge_log;
  EXPECT_EQ(count_in(run.emulator_log, "SET_MESSAGE_INTERVAL"), 2) << run.emulator_log;
  EXPECT_EQ(count_in(run.emulator_log, "resends"), 0) << run.emulator_log;  // not retried
  EXPECT_EQ(count_in(run.bridge_log, "refused"), 2) << run.bridge_log;
  EXPECT_NE(run.bridge_log.find("ATTITUDE_QUATERNION at 200 Hz (5000 us): refused "
                                "(MAV_RESULT_DENIED)"),
            std::string::npos)
      << run.bridge_log;
  EXPECT_TRUE(run.received.empty());
}

// 0.2 m steps at 10 Hz, then a 5 m jump (a relocalisation): the reset counter steps.
constexpr int kPoses = 5;
double east_of(int i) {
  return i < 4 ? 1.0 + 0.2 * i : 6.0;
}

msg::PoseWithCovarianceStamped pose_message(int i) {
  Pose pose;
  pose.stamp = 1700000000.0 + 0.1 * i;
  pose.position = Vec3(east_of(i), 2.0, 3.0);                      // east, north, up
  pose.orientation = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()) *  // facing north
                     Eigen::AngleAxisd(-0.1, Vec3::UnitY());       // nose 0.1 rad up
  msg::PoseWithCovarianceStamped message =
      dds::to_msg(pose, 0.9f, 100 + static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(i),
                  dds::Source{"map", "uav1"});
  message.covariance()[0] = 0.04;  // east variance
  message.covariance()[7] = 0.09;  // north variance
  message.covariance()[35] = 0.01;
  return message;
}

// The lines the emulator recorded after `poses` wrote kPoses poses to an imu_bridge on `port`
// started with `bridge_flags`.
std::vector<std::string> ImuBridgeMavlinkTest::poses_at_autopilot(
    dds::Writer<msg::PoseWithCovarianceStampedPubSubType>& poses, int domain, int port,
    const std::vector<std::string>& bridge_flags) {
  std::vector<std::string> flags{"--source", "mavlink:udp:" + std::to_string(port)};
  flags.insert(flags.end(), bridge_flags.begin(), bridge_flags.end());
  const std::string name = "imu_bridge_" + std::to_string(port);
  ChildProcess bridge(node_argv("imu_bridge", domain, flags), log_path(name));
  EXPECT_TRUE(poses.wait_for_matched(1, 30s)) << bridge.log();
  ChildProcess emulator(emulator_argv(port, 1.0, {"--linger", "30"}), log_path(name + "_emulator"));
  // The bridge answers the autopilot's address once it has heard from it.
  EXPECT_TRUE(wait_for_log(bridge, "autopilot heard", 30s)) << bridge.log();
  for (int i = 0; i < kPoses; ++i) EXPECT_TRUE(poses.write(pose_message(i)));
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (record().size() < static_cast<std::size_t>(kPoses) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);
  }
  emulator.stop(5s);
  EXPECT_EQ(bridge.stop(10s), 0) << bridge.log();
  // This bridge's reader gone before the next bridge joins.
  const auto unmatched_by = std::chrono::steady_clock::now() + 30s;
  while (poses.matched() > 0 && std::chrono::steady_clock::now() < unmatched_by) {
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_EQ(poses.matched(), 0u);
  const std::vector<std::string> lines = record();
  std::filesystem::remove(path("poses.txt"));
  return lines;
}

// A pose writer stands in for the matcher; the emulator records what reaches the autopilot.
TEST_F(ImuBridgeMavlinkTest, SendsPosesToTheAutopilotInNed) {
  constexpr int kDomain = 199;
  dds::Participant participant(kDomain, dds::default_profiles_path(), "uavslam_loopback", "test");
  dds::Writer<msg::PoseWithCovarianceStampedPubSubType> poses(
      participant, dds::topic_name("uav1", dds::kPoseTopic), "state_writer");

  const std::vector<std::string> vision = poses_at_autopilot(poses, kDomain, 24553, {});
  ASSERT_EQ(vision.size(), static_cast<std::size_t>(kPoses));
  for (int i = 0; i < kPoses; ++i) {
    std::istringstream fields(vision[static_cast<std::size_t>(i)]);
    std::string kind;
    unsigned long long usec = 0;
    double x, y, z, roll, pitch, yaw, cov_xx, cov_yy, cov_yaw;
    int reset = -1;
    fields >> kind >> usec >> x >> y >> z >> roll >> pitch >> yaw >> reset >> cov_xx >> cov_yy >>
        cov_yaw;
    EXPECT_EQ(kind, "vision");
    EXPECT_EQ(usec, 1700000000000000ull + 100000ull * static_cast<unsigned>(i));
    EXPECT_NEAR(x, 2.0, 1e-6);         // north
    EXPECT_NEAR(y, east_of(i), 1e-6);  // east
    EXPECT_NEAR(z, -3.0, 1e-6);        // down
    EXPECT_NEAR(roll, 0.0, 1e-6);
    EXPECT_NEAR(pitch, 0.1, 1e-6);  // nose up is positive in FRD
    EXPECT_NEAR(yaw, 0.0, 1e-6);    // north
    EXPECT_EQ(reset, i < 4 ? 0 : 1);
    EXPECT_NEAR(cov_xx, 0.09, 1e-7);  // north variance
    EXPECT_NEAR(cov_yy, 0.04, 1e-7);
    EXPECT_NEAR(cov_yaw, 0.01, 1e-7);
  }

  const std::vector<std::string> odometry =
      poses_at_autopilot(poses, kDomain, 24554, {"--mavlink-pose", "odometry"});
  ASSERT_EQ(odometry.size(), static_cast<std::size_t>(kPoses));
  for (int i = 0; i < kPoses; ++i) {
    std::istringstream fields(odometry[static_cast<std::size_t>(i)]);
    std::string kind;
    unsigned long long usec = 0;
    double x, y, z, qw, qx, qy, qz;
    int reset = -1, quality = 0, frame = 0, child = 0;
    fields >> kind >> usec >> x >> y >> z >> qw >> qx >> qy >> qz >> reset >> quality >> frame >>
        child;
    EXPECT_EQ(kind, "odometry");
    EXPECT_NEAR(x, 2.0, 1e-6);
    EXPECT_NEAR(y, east_of(i), 1e-6);
    EXPECT_NEAR(z, -3.0, 1e-6);
    // Facing north, nose 0.1 rad up: a rotation of +0.1 rad about FRD y (right).
    EXPECT_NEAR(std::abs(qw), std::cos(0.05), 1e-6);
    EXPECT_NEAR(qy * (qw < 0 ? -1 : 1), std::sin(0.05), 1e-6);
    EXPECT_NEAR(qx, 0.0, 1e-6);
    EXPECT_NEAR(qz, 0.0, 1e-6);
    EXPECT_EQ(reset, i < 4 ? 0 : 1);
    EXPECT_EQ(quality, 90);
    EXPECT_EQ(frame, 1);   // MAV_FRAME_LOCAL_NED
    EXPECT_EQ(child, 12);  // MAV_FRAME_BODY_FRD
  }
}

}  // namespace
}  // namespace uavslam::test
