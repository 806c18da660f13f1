// Replaying an MCAP recording over DDS: `uavslam simulate --log` records the short flight, then
// lidar_driver and imu_bridge (--source mcap:FILE, one --start-at timeline) replay it into a real
// slam_matcher (--sensor: the scenario's mount and mirror) on their own domains (170-172), the test
// as a ground-side subscriber of `pose` and `matcher_status`, scored against the recording's own
// ground_truth channel. Damaged, foreign and missing files are named, never a crash.
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <msg/ImuPubSubTypes.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <msg/TwistPubSubTypes.h>

#include "MatcherListener.hpp"
#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/RecordedMessageStream.hpp"
#include "dds/SimulatedSensorMessages.hpp"
#include "dds/Topics.hpp"
#include "eval/TrajectoryMetrics.hpp"

namespace uavslam {
namespace {

using test::MatcherCounts;
using test::MatcherListener;

using namespace std::chrono_literals;
using ::testing::HasSubstr;

constexpr int kDomain = 170;         // the whole flight's replay
constexpr int kDamagedDomain = 172;  // the cut recording's
const std::string kScenario = std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/short.yaml";

// The recording's ground_truth channel, by stamp in ns.
std::map<std::int64_t, Pose> recorded_truth(const std::string& log) {
  dds::RecordedMessageStream stream(log, {dds::kGroundTruthTopic});
  std::map<std::int64_t, Pose> truth;
  while (std::optional<dds::RecordedMessage> m = stream.next()) {
    const Pose pose = dds::from_msg(std::get<msg::PoseWithCovarianceStamped>(m->sample));
    truth[std::llround(pose.stamp * 1e9)] = pose;
  }
  return truth;
}

class McapReplay : public test::ProcessTest {
 protected:
  // `uavslam simulate` of the short flight, recorded to OUT/short.mcap.
  std::string record_short_flight() {
    const std::string log = path("short.mcap");
    process::ChildProcess simulate({binary("uavslam"), "simulate", "--quiet", "--scenario",
                                    kScenario, "--out", path("simulate"), "--log", log},
                                   log_path("simulate"));
    EXPECT_TRUE(simulate.wait(120s)) << simulate.log();
    EXPECT_EQ(simulate.exit_code(), 0) << simulate.log();
    return log;
  }

  static std::vector<std::string> sensor(const char* name, int domain, const std::string& log,
                                         const std::string& start_at) {
    return node_argv(name, domain,
                     {"--vehicle", "uav1", "--source", "mcap:" + log, "--rate", "4", "--start-at",
                      start_at, "--wait-for-subscribers", "1"});
  }
};

TEST_F(McapReplay, ARecordedFlightReplaysIntoTheMatcherOnTrack) {
  const std::string log = record_short_flight();
  ASSERT_FALSE(HasFailure());

  MatcherListener listener(kDomain, "uav1");
  process::ChildProcess matcher(
      node_argv("slam_matcher", kDomain,
                {"--vehicle", "uav1", "--sensor", kScenario, "--slam-config",
                 std::string(UAVSLAM_SOURCE_DIR) + "/config/slam.yaml"}),
      log_path("slam_matcher"));
  ASSERT_TRUE(listener.matched()) << matcher.log();
  const std::string start_at = shared_start_time();
  process::ChildProcess imu(sensor("imu_bridge", kDomain, log, start_at), log_path("imu_bridge"));
  process::ChildProcess lidar(sensor("lidar_driver", kDomain, log, start_at),
                              log_path("lidar_driver"));
  ASSERT_TRUE(lidar.wait(60s)) << lidar.log();
  EXPECT_EQ(lidar.exit_code(), 0) << lidar.log();
  ASSERT_TRUE(imu.wait(60s)) << imu.log();
  EXPECT_EQ(imu.exit_code(), 0) << imu.log();
  EXPECT_TRUE(listener.wait_for_scan(800, 10s)) << matcher.log();
  EXPECT_EQ(matcher.stop(10s), 0) << matcher.log();
  std::cerr << lidar.log() << imu.log() << matcher.log();

  EXPECT_THAT(lidar.log(), HasSubstr("published 801 scans of " + log + ", 0 malformed"));
  EXPECT_THAT(imu.log(), HasSubstr("published 4001 samples of " + log + ", 0 malformed"));
  EXPECT_THAT(matcher.log(), HasSubstr("801 scans received"));

  const std::map<std::int64_t, Pose> truth = recorded_truth(log);
  ASSERT_EQ(truth.size(), 801u);
  const std::vector<Pose> poses = listener.poses();
  ASSERT_GE(poses.size(), 720u) << "of 801 scans\n" << matcher.log();
  std::vector<Pose> ground_truth;
  for (const Pose& p : poses) {
    const auto found = truth.find(std::llround(p.stamp * 1e9));
    ASSERT_NE(found, truth.end()) << "a pose at " << p.stamp << " s, where no scan was recorded";
    ground_truth.push_back(found->second);
  }
  const eval::TrajectoryErrors errors = eval::compare_trajectories(poses, ground_truth);
  std::cerr << "poses " << poses.size() << ", ATE horizontal " << errors.ate_horizontal_rmse
            << " m, vertical " << errors.ate_vertical_rmse << " m\n";
  EXPECT_LT(errors.ate_horizontal_rmse, 0.10);
  EXPECT_LT(errors.ate_vertical_rmse, 0.10);
}

// A flight with the autopilot's velocity (flow_corridor.yaml): imu_bridge replays the recording's
// `velocity` channel beside `imu`, every sample of it.
TEST_F(McapReplay, TheAutopilotsVelocityIsReplayedBesideTheImu) {
  constexpr int kVelocityDomain = 201;
  const std::string log = path("flow.mcap");
  process::ChildProcess simulate(
      {binary("uavslam"), "simulate", "--quiet", "--scenario",
       std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/flow_corridor.yaml", "--out",
       path("simulate"), "--log", log},
      log_path("simulate"));
  ASSERT_TRUE(simulate.wait(120s)) << simulate.log();
  ASSERT_EQ(simulate.exit_code(), 0) << simulate.log();
  std::size_t recorded = 0;
  dds::RecordedMessageStream stream(log, {dds::kVelocityTopic});
  while (stream.next()) ++recorded;
  ASSERT_EQ(recorded, 541u) << "27 s at 20 Hz";

  dds::Participant ground(kVelocityDomain, dds::default_profiles_path(), "uavslam_loopback",
                          "test");
  std::mutex mutex;
  std::vector<VelocitySample> velocities;
  dds::Reader<msg::TwistWithCovarianceStampedPubSubType> velocity_reader(
      ground, dds::topic_name("uav1", dds::kVelocityTopic), "sensor_reader",
      [&](const msg::TwistWithCovarianceStamped& m, const auto&) {
        const std::lock_guard<std::mutex> lock(mutex);
        velocities.push_back(dds::from_msg(m));
      });
  dds::Reader<msg::ImuPubSubType> imu_reader(ground, dds::topic_name("uav1", dds::kImuTopic),
                                             "sensor_reader", [](const msg::Imu&, const auto&) {});
  process::ChildProcess imu(sensor("imu_bridge", kVelocityDomain, log, shared_start_time()),
                            log_path("imu_bridge"));
  ASSERT_TRUE(imu.wait(60s)) << imu.log();
  EXPECT_EQ(imu.exit_code(), 0) << imu.log();
  velocity_reader.wait_for_received(recorded, 10s);
  const std::lock_guard<std::mutex> lock(mutex);
  EXPECT_EQ(velocities.size(), recorded) << imu.log();
  ASSERT_FALSE(velocities.empty());
  EXPECT_TRUE(velocities.front().covariance.isApprox(0.0025 * Eigen::Matrix3d::Identity()));
}

TEST_F(McapReplay, ACutRecordingReplaysItsCompletePartAndSaysWhereItStopped) {
  const std::string log = record_short_flight();
  ASSERT_FALSE(HasFailure());
  const std::string cut = path("cut.mcap");
  std::filesystem::copy_file(log, cut);
  std::filesystem::resize_file(cut, std::filesystem::file_size(log) / 2);

  // Nobody listens: the replay publishes at 50x into the void, and ends at the damage.
  process::ChildProcess lidar(
      node_argv("lidar_driver", kDamagedDomain, {"--source", "mcap:" + cut, "--rate", "50"}),
      log_path("lidar_driver"));
  ASSERT_TRUE(lidar.wait(60s)) << lidar.log();
  EXPECT_EQ(lidar.exit_code(), 0) << lidar.log();
  EXPECT_THAT(lidar.log(), HasSubstr(cut + ": the log stops at byte"));
  EXPECT_THAT(lidar.log(), HasSubstr("truncated inside"));
  EXPECT_THAT(lidar.log(), ::testing::ContainsRegex("published [1-9][0-9]+ scans of"));
  EXPECT_THAT(lidar.log(), ::testing::Not(HasSubstr("published 801 scans")));
}

TEST_F(McapReplay, AMissingOrForeignRecordingIsNamedWithExitCode2) {
  const std::string missing = path("missing.mcap");
  process::ChildProcess lidar(
      node_argv("lidar_driver", kDamagedDomain, {"--source", "mcap:" + missing}),
      log_path("lidar_driver"));
  ASSERT_TRUE(lidar.wait(30s));
  EXPECT_EQ(lidar.exit_code(), 2) << lidar.log();
  EXPECT_THAT(lidar.log(), HasSubstr(missing + ": cannot open"));

  const std::string foreign = write("scan.mcap", "FLASER 3 1 1 1\n");
  process::ChildProcess imu(
      node_argv("imu_bridge", kDamagedDomain, {"--source", "mcap:" + foreign}),
      log_path("imu_bridge"));
  ASSERT_TRUE(imu.wait(30s));
  EXPECT_EQ(imu.exit_code(), 2) << imu.log();
  EXPECT_THAT(imu.log(), HasSubstr(foreign + ": not an MCAP file"));
}

}  // namespace
}  // namespace uavslam
