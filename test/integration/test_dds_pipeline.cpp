// The distributed system end to end: lidar_driver, imu_bridge and slam_matcher as separate OS
// processes over DDS on loopback (their own domain), the test as a ground-side subscriber.
#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <mutex>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/PosePubSubTypes.h>

#include "ChildProcess.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "eval/TrajectoryMetrics.hpp"
#include "io/ScenarioFile.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr int kDomain = 171;  // this test's own DDS domain
const std::string kScenario = std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/short.yaml";

// The flight's start on the system clock, shared by both sensor processes (--start-at), far
// enough ahead for them to discover the matcher first.
std::string shared_start_time() {
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  return std::to_string(std::chrono::duration<double>(now).count() + 3.0);
}

std::string binary(const char* name) {
  return std::string(UAVSLAM_BIN_DIR) + "/" + name;
}

class DdsPipeline : public ::testing::Test {
 protected:
  fs::path dir;
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "uavslam_dds_XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir = pattern;
  }
  void TearDown() override {
    fs::remove_all(dir);
    // Processes that were killed leave their shared-memory segments behind.
    if (std::system("fastdds shm clean > /dev/null 2>&1") != 0) {
      ADD_FAILURE() << "fastdds shm clean failed";
    }
  }
  std::vector<std::string> node(const char* name, std::vector<std::string> extra) const {
    std::vector<std::string> argv{binary(name), "--domain", std::to_string(kDomain), "--vehicle",
                                  "uav1"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return argv;
  }
  std::string log(const char* name) const { return (dir / (std::string(name) + ".log")).string(); }
};

TEST_F(DdsPipeline, ThreeProcessesTrackTheShortFlight) {
  dds::Participant ground(kDomain, dds::default_profiles_path(), "uavslam_loopback", "test");
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<Pose> poses;
  std::uint64_t last_status_scan = 0;
  std::string last_outcome;
  dds::Reader<msg::PoseWithCovarianceStampedPubSubType> pose_reader(
      ground, dds::topic_name("uav1", dds::kPoseTopic), "state_reader",
      [&](const msg::PoseWithCovarianceStamped& m, const eprosima::fastdds::dds::SampleInfo&) {
        std::lock_guard<std::mutex> lock(mutex);
        poses.push_back(dds::from_msg(m));
      });
  dds::Reader<msg::MatcherStatusPubSubType> status_reader(
      ground, dds::topic_name("uav1", dds::kMatcherStatusTopic), "status_reader",
      [&](const msg::MatcherStatus& m, const eprosima::fastdds::dds::SampleInfo&) {
        {
          std::lock_guard<std::mutex> lock(mutex);
          last_status_scan = m.scan_seq();
          last_outcome = m.outcome();
        }
        changed.notify_all();
      });

  test::ChildProcess matcher(
      node("slam_matcher", {"--sensor", kScenario, "--slam-config",
                            std::string(UAVSLAM_SOURCE_DIR) + "/config/slam.yaml"}),
      log("slam_matcher"));
  ASSERT_TRUE(matcher.started());
  ASSERT_TRUE(pose_reader.wait_for_matched(1, 30s)) << matcher.log();
  ASSERT_TRUE(status_reader.wait_for_matched(1, 30s)) << matcher.log();

  // The sensors start once the matcher's readers have matched them: no scan is lost to discovery.
  const std::string start_at = shared_start_time();
  test::ChildProcess imu(
      node("imu_bridge", {"--scenario", kScenario, "--rate", "4", "--wait-for-subscribers", "1",
                          "--start-at", start_at}),
      log("imu_bridge"));
  test::ChildProcess lidar(
      node("lidar_driver", {"--scenario", kScenario, "--rate", "4", "--wait-for-subscribers", "1",
                            "--start-at", start_at}),
      log("lidar_driver"));
  ASSERT_TRUE(lidar.wait(60s)) << lidar.log();
  EXPECT_EQ(lidar.exit_code(), 0) << lidar.log();
  ASSERT_TRUE(imu.wait(60s)) << imu.log();
  EXPECT_EQ(imu.exit_code(), 0) << imu.log();

  // The last scan (sequence 800) is processed, or the matcher goes quiet.
  {
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait_for(lock, 10s, [&] { return last_status_scan >= 800; });
  }
  EXPECT_EQ(matcher.stop(10s), 0) << matcher.log();
  EXPECT_THAT(matcher.log(), ::testing::HasSubstr("scans received"));

  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_GE(poses.size(), 720u) << "of 801 scans\n" << matcher.log() << imu.log() << lidar.log();
  std::cerr << imu.log() << lidar.log();
  sim::FlightSimulator truth(io::load_scenario(kScenario));
  std::vector<Pose> ground_truth;
  for (const Pose& p : poses) ground_truth.push_back(truth.ground_truth_at(p.stamp));
  const eval::TrajectoryErrors errors = eval::compare_trajectories(poses, ground_truth);
  std::cerr << "poses " << poses.size() << ", ATE horizontal " << errors.ate_horizontal_rmse
            << " m, vertical " << errors.ate_vertical_rmse << " m; matcher: " << matcher.log();
  EXPECT_LT(errors.ate_horizontal_rmse, 0.10);
  EXPECT_LT(errors.ate_vertical_rmse, 0.10);
}

TEST_F(DdsPipeline, ABadProfileFileIsNamedAndRefused) {
  const std::string bad = (dir / "bad.xml").string();
  std::ofstream(bad) << "<dds><profiles><participant profile_name=\"x\"><rtps><nope/></rtps>"
                        "</participant></profiles></dds>";
  test::ChildProcess lidar(node("lidar_driver", {"--scenario", kScenario, "--qos", bad}),
                           log("lidar_driver"));
  ASSERT_TRUE(lidar.wait(30s));
  EXPECT_EQ(lidar.exit_code(), 2);
  EXPECT_THAT(lidar.log(), ::testing::HasSubstr(bad));

  test::ChildProcess matcher(
      node("slam_matcher", {"--sensor", kScenario, "--participant-profile", "no_such_profile"}),
      log("slam_matcher"));
  ASSERT_TRUE(matcher.wait(30s));
  EXPECT_EQ(matcher.exit_code(), 2);
  EXPECT_THAT(matcher.log(), ::testing::HasSubstr("no_such_profile"));
}

}  // namespace
}  // namespace uavslam
