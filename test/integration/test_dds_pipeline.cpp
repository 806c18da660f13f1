// The distributed system end to end: lidar_driver, imu_bridge and slam_matcher as separate OS
// processes over DDS on loopback (their own domain), the test as a ground-side subscriber.
#include <chrono>
#include <condition_variable>
#include <fstream>
#include <iostream>
#include <iterator>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/PosePubSubTypes.h>

#include "BackEndCorrections.hpp"
#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "eval/TrajectoryMetrics.hpp"
#include "io/ScenarioFile.hpp"
#include "io/TumFile.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam {
namespace {

using namespace std::chrono_literals;

constexpr int kDomain = 171;              // this test's own DDS domain
constexpr int kIncompatibleDomain = 190;  // the incompatible-QoS test's
constexpr int kCorridorDomain = 179;      // the plain corridor's
constexpr int kVelocityDomain = 202;      // the corridor with the autopilot's velocity
constexpr int kLoopDomain = 108;          // the drifting IMU's flight with the back end
const std::string kScenario = std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/short.yaml";

// What the ground saw of one scenario flown by lidar_driver, imu_bridge and slam_matcher (with
// config/slam.yaml) over DDS, and the ATE of its poses.
struct FlightOverDds {
  std::vector<msg::PoseWithCovarianceStamped> poses;
  std::vector<msg::MatcherStatus> statuses;
  std::string matcher_log;
  std::string map_server_log;      // with_map_server only
  std::string ground_station_out;  // likewise: where the ground station wrote its files
  double ate_horizontal = 0.0;
};

class DdsPipeline : public test::ProcessTest {
 protected:
  // The matcher's readers match the ground's first, then the sensors start on a shared timeline;
  // the flight ends when the status of its last scan (`last_scan`) comes, or the matcher goes
  // quiet.
  // with_map_server: a map server and a ground station run beside the matcher.
  // slam_config: the matcher's, config/slam.yaml when empty.
  FlightOverDds fly_over_dds(const std::string& scenario, int domain, const std::string& label,
                             std::uint64_t last_scan, bool with_map_server = false,
                             const std::string& slam_config = "");

  // A process of this test: on its own domain, for vehicle uav1.
  static std::vector<std::string> node(const char* name, std::vector<std::string> extra,
                                       int domain = kDomain) {
    extra.insert(extra.begin(), {"--vehicle", "uav1"});
    return node_argv(name, domain, extra);
  }
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

  process::ChildProcess matcher(
      node("slam_matcher", {"--sensor", kScenario, "--slam-config",
                            std::string(UAVSLAM_SOURCE_DIR) + "/config/slam.yaml"}),
      log_path("slam_matcher"));
  ASSERT_TRUE(matcher.started());
  ASSERT_TRUE(pose_reader.wait_for_matched(1, 30s)) << matcher.log();
  ASSERT_TRUE(status_reader.wait_for_matched(1, 30s)) << matcher.log();

  // The sensors start once the matcher's readers have matched them: no scan is lost to discovery.
  const std::string start_at = shared_start_time();
  process::ChildProcess imu(node("imu_bridge", sensor_flags(kScenario, start_at)),
                            log_path("imu_bridge"));
  process::ChildProcess lidar(node("lidar_driver", sensor_flags(kScenario, start_at)),
                              log_path("lidar_driver"));
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
  // The scanner's sweep, from the sensor file and each scan's time_increment, is undone.
  EXPECT_THAT(matcher.log(),
              ::testing::HasSubstr("each beam placed from where the vehicle was when it fired"));

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

FlightOverDds DdsPipeline::fly_over_dds(const std::string& scenario, int domain,
                                        const std::string& label, std::uint64_t last_scan,
                                        bool with_map_server, const std::string& slam_config) {
  FlightOverDds flight;
  dds::Participant ground(domain, dds::default_profiles_path(), "uavslam_loopback", "test");
  std::mutex mutex;
  std::condition_variable changed;
  std::uint64_t last_status_scan = 0;
  dds::Reader<msg::PoseWithCovarianceStampedPubSubType> pose_reader(
      ground, dds::topic_name("uav1", dds::kPoseTopic), "state_reader",
      [&](const msg::PoseWithCovarianceStamped& m, const eprosima::fastdds::dds::SampleInfo&) {
        std::lock_guard<std::mutex> lock(mutex);
        flight.poses.push_back(m);
      });
  dds::Reader<msg::MatcherStatusPubSubType> status_reader(
      ground, dds::topic_name("uav1", dds::kMatcherStatusTopic), "status_reader",
      [&](const msg::MatcherStatus& m, const eprosima::fastdds::dds::SampleInfo&) {
        {
          std::lock_guard<std::mutex> lock(mutex);
          last_status_scan = m.scan_seq();
          flight.statuses.push_back(m);
        }
        changed.notify_all();
      });

  std::optional<process::ChildProcess> map_server;
  std::optional<process::ChildProcess> station;
  if (with_map_server) {
    map_server.emplace(node("map_server", {"--publish-period", "0.5"}, domain),
                       log_path("map_server_" + label));
    flight.ground_station_out = path("ground_station_" + label);
    station.emplace(node("ground_station", {"--quiet", "--out", flight.ground_station_out}, domain),
                    log_path("ground_station_" + label));
  }
  const std::string config =
      slam_config.empty() ? std::string(UAVSLAM_SOURCE_DIR) + "/config/slam.yaml" : slam_config;
  process::ChildProcess matcher(
      node("slam_matcher", {"--sensor", scenario, "--slam-config", config}, domain),
      log_path("slam_matcher_" + label));
  EXPECT_TRUE(matcher.started());
  EXPECT_TRUE(pose_reader.wait_for_matched(1, 30s)) << matcher.log();
  EXPECT_TRUE(status_reader.wait_for_matched(1, 30s)) << matcher.log();
  const std::string start_at = shared_start_time();
  process::ChildProcess imu(node("imu_bridge", sensor_flags(scenario, start_at), domain),
                            log_path("imu_bridge_" + label));
  process::ChildProcess lidar(node("lidar_driver", sensor_flags(scenario, start_at), domain),
                              log_path("lidar_driver_" + label));
  EXPECT_TRUE(lidar.wait(120s)) << lidar.log();
  EXPECT_EQ(lidar.exit_code(), 0) << lidar.log();
  EXPECT_TRUE(imu.wait(120s)) << imu.log();
  EXPECT_EQ(imu.exit_code(), 0) << imu.log();
  {
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait_for(lock, 10s, [&] { return last_status_scan >= last_scan; });
  }
  EXPECT_EQ(matcher.stop(10s), 0) << matcher.log();
  flight.matcher_log = matcher.log();
  std::cerr << imu.log() << lidar.log() << flight.matcher_log;
  if (map_server) {
    EXPECT_EQ(map_server->stop(10s), 0) << map_server->log();
    flight.map_server_log = map_server->log();
    std::cerr << flight.map_server_log;
  }
  if (station) {
    EXPECT_EQ(station->stop(20s), 0) << station->log();
  }

  std::lock_guard<std::mutex> lock(mutex);
  sim::FlightSimulator truth(io::load_scenario(scenario));
  std::vector<Pose> poses;
  std::vector<Pose> ground_truth;
  for (const msg::PoseWithCovarianceStamped& m : flight.poses) {
    poses.push_back(dds::from_msg(m));
    ground_truth.push_back(truth.ground_truth_at(poses.back().stamp));
  }
  if (!poses.empty()) {
    flight.ate_horizontal = eval::compare_trajectories(poses, ground_truth).ate_horizontal_rmse;
  }
  std::cerr << label << ": poses " << poses.size() << ", ATE horizontal " << flight.ate_horizontal
            << " m\n";
  return flight;
}

// The plain corridor (issue 17) over DDS: along its axis the scan is blind. Every airborne status
// says so (degraded: degenerate), and every pose's covariance says which way: metres along the
// axis, centimetres across. The vehicle is carried down the corridor by the IMU, and a rejected
// scan still gets its pose, dead-reckoned (quality 0), so the pose stream has no holes.
TEST_F(DdsPipeline, ThePlainCorridorsBlindAxisIsOnTheWire) {
  const FlightOverDds flight =
      fly_over_dds(std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/plain_corridor.yaml",
                   kCorridorDomain, "corridor", 1080);
  std::size_t blind_poses = 0;  // axis sigma over a hundred times the lateral one
  std::size_t dead_reckoned = 0;
  for (const msg::PoseWithCovarianceStamped& m : flight.poses) {
    const auto& c = m.covariance();
    blind_poses += c[0] > 100.0 * c[7] && c[7] > 0.0 && c[35] > 0.0;
    dead_reckoned += m.quality() == 0.0f;
  }
  std::size_t degenerate = 0;
  std::size_t rejected = 0;
  for (const msg::MatcherStatus& m : flight.statuses) {
    rejected += m.outcome() != "accepted" && m.outcome() != "map_initialised";
    degenerate += m.tracking() == "degraded" && m.tracking_reason() == "degenerate" &&
                  m.degenerate_directions() == 1;
  }
  const std::size_t statuses = flight.statuses.size();
  const std::size_t poses = flight.poses.size();
  ASSERT_GE(poses, 950u) << "of 1081 scans\n" << flight.matcher_log;
  EXPECT_GE(degenerate, statuses * 9 / 10) << statuses << " statuses";
  EXPECT_GE(blind_poses, poses * 9 / 10) << poses << " poses";
  EXPECT_GT(rejected, 0u) << "the flight has rejected scans (error_increased)";
  // Both streams are reliable with a history of 10: a loaded machine may drop a few samples.
  EXPECT_LE(dead_reckoned, rejected);
  EXPECT_GE(dead_reckoned * 10, rejected * 9) << "each rejected scan's pose, carried by the IMU";
  EXPECT_GE(poses * 100, statuses * 98) << "a pose for every scan";
  EXPECT_LT(flight.ate_horizontal, 0.25);
}

// The corridor flown with a biased accelerometer and the autopilot's optical-flow velocity
// (flow_corridor.yaml): imu_bridge publishes `velocity` beside `imu`, the matcher fuses it (the
// shipped config's motion.fuse_velocity), and the vehicle is carried down the corridor where the
// IMU alone ends metres off (uavslam simulate: 3.3 m).
// The drifting IMU's flight (yaw_drift.yaml, 180 s at 4x) with the shipped back end: the matcher
// closes loops on its own thread and publishes each correction (`keyframe_poses`), and the map
// server moves its keyframes and rebuilds its map with every one. The heading is checked
// periodically (config/slam.yaml otherwise): taken from every scan, as shipped, the drift no
// longer bends the map and there is nothing to correct.
TEST_F(DdsPipeline, TheBackEndsCorrectionsReachTheMapServer) {
  std::ifstream shipped(std::string(UAVSLAM_SOURCE_DIR) + "/config/slam.yaml");
  std::string config((std::istreambuf_iterator<char>(shipped)), {});
  const std::string every_scan = "\n  heading: every_scan";
  const std::size_t at = config.find(every_scan);
  ASSERT_NE(at, std::string::npos) << "config/slam.yaml's heading";
  config.replace(at, every_scan.size(), "\n  heading: periodic_check");
  const std::string checked = path("slam_periodic_check.yaml");
  std::ofstream(checked) << config;
  const FlightOverDds flight =
      fly_over_dds(std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/yaw_drift.yaml",
                   kLoopDomain, "loops", 7200, true, checked);
  ASSERT_FALSE(HasFailure());
  // Published by the matcher, applied by the map server; the ground station heard the corrections
  // too and wrote where the keyframes now are.
  const std::optional<test::FollowedCorrections> followed = test::expect_corrections_followed(
      flight.matcher_log, flight.map_server_log, flight.ground_station_out);
  ASSERT_TRUE(followed);
  EXPECT_GE(flight.poses.size(), 6500u) << "of 7201 scans";
  EXPECT_LT(flight.ate_horizontal, 0.25);
  // The matcher's status said so as it flew.
  EXPECT_GT(followed->summary["matcher_status"]["loops_accepted"].get<int>(), 0);
  EXPECT_GT(followed->keyframes, 100u);
  // And each pose where the final graph puts its keyframe: closer to the truth than as flown.
  const std::vector<Pose> corrected =
      io::read_tum(flight.ground_station_out + "/trajectory_corrected.tum");
  ASSERT_GE(corrected.size(), 6500u);
  sim::FlightSimulator truth(
      io::load_scenario(std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/yaw_drift.yaml"));
  std::vector<Pose> ground_truth;
  for (const Pose& p : corrected) ground_truth.push_back(truth.ground_truth_at(p.stamp));
  const double after = eval::compare_trajectories(corrected, ground_truth).ate_horizontal_rmse;
  std::cerr << "ground station: corrected trajectory ATE horizontal " << after << " m\n";
  EXPECT_LT(after, flight.ate_horizontal);
}

TEST_F(DdsPipeline, TheAutopilotsVelocityOnTheWireCarriesTheCorridor) {
  const FlightOverDds flight =
      fly_over_dds(std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/flow_corridor.yaml",
                   kVelocityDomain, "velocity", 1080);
  ASSERT_GE(flight.poses.size(), 950u) << "of 1081 scans\n" << flight.matcher_log;
  EXPECT_THAT(flight.matcher_log,
              ::testing::ContainsRegex("velocity: [1-9][0-9]* samples received, 0 dropped"));
  EXPECT_LT(flight.ate_horizontal, 0.3);
}

// The shipped sensor file of a real UTM-30LX (config/sensors: 1081 steps of 0.25 deg, no world)
// against the simulated scanner's 1080 beams over the same 270 deg, on the same mount and mirror:
// the matcher matches the scans with their own layout on the file's mount and tracks the flight.
TEST_F(DdsPipeline, ScansWithAnotherBeamCountThanTheSensorFileAreMatchedOnItsMount) {
  constexpr int kLayoutDomain = 200;
  dds::Participant ground(kLayoutDomain, dds::default_profiles_path(), "uavslam_loopback", "test");
  std::mutex mutex;
  std::vector<Pose> poses;
  dds::Reader<msg::PoseWithCovarianceStampedPubSubType> pose_reader(
      ground, dds::topic_name("uav1", dds::kPoseTopic), "state_reader",
      [&](const msg::PoseWithCovarianceStamped& m, const eprosima::fastdds::dds::SampleInfo&) {
        std::lock_guard<std::mutex> lock(mutex);
        poses.push_back(dds::from_msg(m));
      });
  const auto on_domain = [](const char* name, std::vector<std::string> extra) {
    extra.insert(extra.begin(), {"--vehicle", "uav1"});
    return node_argv(name, kLayoutDomain, extra);
  };
  process::ChildProcess matcher(
      on_domain(
          "slam_matcher",
          {"--sensor", std::string(UAVSLAM_SOURCE_DIR) + "/config/sensors/hokuyo_utm30lx.yaml",
           "--initial-position", "3,3,0.3",  // the short flight's first waypoint
           "--slam-config", std::string(UAVSLAM_SOURCE_DIR) + "/config/slam.yaml"}),
      log_path("slam_matcher"));
  ASSERT_TRUE(matcher.started());
  ASSERT_TRUE(pose_reader.wait_for_matched(1, 30s)) << matcher.log();
  const std::string start_at = shared_start_time();
  process::ChildProcess imu(on_domain("imu_bridge", sensor_flags(kScenario, start_at)),
                            log_path("imu_bridge"));
  process::ChildProcess lidar(on_domain("lidar_driver", sensor_flags(kScenario, start_at)),
                              log_path("lidar_driver"));
  ASSERT_TRUE(lidar.wait(60s)) << lidar.log();
  ASSERT_TRUE(imu.wait(60s)) << imu.log();
  EXPECT_EQ(matcher.stop(10s), 0) << matcher.log();
  EXPECT_THAT(matcher.log(), ::testing::HasSubstr("the scans have 1080 beams"));

  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_GE(poses.size(), 720u) << "of 801 scans\n" << matcher.log();
  sim::FlightSimulator truth(io::load_scenario(kScenario));
  std::vector<Pose> ground_truth;
  for (const Pose& p : poses) ground_truth.push_back(truth.ground_truth_at(p.stamp));
  const eval::TrajectoryErrors errors = eval::compare_trajectories(poses, ground_truth);
  std::cerr << "poses " << poses.size() << ", ATE horizontal " << errors.ate_horizontal_rmse
            << " m, vertical " << errors.ate_vertical_rmse << " m\n";
  EXPECT_LT(errors.ate_horizontal_rmse, 0.10);
  EXPECT_LT(errors.ate_vertical_rmse, 0.10);
}

TEST_F(DdsPipeline, ABadProfileFileIsNamedAndRefused) {
  const std::string bad = path("bad.xml");
  std::ofstream(bad) << "<dds><profiles><participant profile_name=\"x\"><rtps><nope/></rtps>"
                        "</participant></profiles></dds>";
  process::ChildProcess lidar(node("lidar_driver", {"--scenario", kScenario, "--qos", bad}),
                              log_path("lidar_driver"));
  ASSERT_TRUE(lidar.wait(30s));
  EXPECT_EQ(lidar.exit_code(), 2);
  EXPECT_THAT(lidar.log(), ::testing::HasSubstr(bad));

  process::ChildProcess matcher(
      node("slam_matcher", {"--sensor", kScenario, "--participant-profile", "no_such_profile"}),
      log_path("slam_matcher"));
  ASSERT_TRUE(matcher.wait(30s));
  EXPECT_EQ(matcher.exit_code(), 2);
  EXPECT_THAT(matcher.log(), ::testing::HasSubstr("no_such_profile"));
}

TEST_F(DdsPipeline, AScanWriterThatCannotServeTheMatcherStopsIt) {
  dds::Participant vehicle(kIncompatibleDomain, dds::default_profiles_path(), "uavslam_loopback",
                           "test");
  // The matcher's scan reader asks for RELIABLE (--profile), the sensor writes BEST_EFFORT.
  process::ChildProcess matcher(
      node_argv("slam_matcher", kIncompatibleDomain,
                {"--sensor", kScenario, "--profile", "scan=state_reader"}),
      log_path("slam_matcher"));
  dds::Writer<msg::LaserScanPubSubType> scans(vehicle, dds::topic_name("uav1", dds::kScanTopic),
                                              "sensor_writer");
  ASSERT_TRUE(scans.wait_for_incompatible_qos(1, 30s)) << matcher.log();
  ASSERT_TRUE(matcher.wait(30s)) << matcher.log();
  EXPECT_EQ(matcher.exit_code(), 1);
  EXPECT_THAT(matcher.log(), ::testing::HasSubstr("incompatible QoS on topic 'uav1/scan'"));
  EXPECT_THAT(matcher.log(), ::testing::HasSubstr("state_reader"));
  EXPECT_THAT(matcher.log(), ::testing::HasSubstr("RELIABILITY"));

  process::ChildProcess typo(node("slam_matcher", {"--sensor", kScenario, "--profile", "scna=x"}),
                             log_path("typo"));
  ASSERT_TRUE(typo.wait(30s));
  EXPECT_EQ(typo.exit_code(), 2);
  EXPECT_THAT(typo.log(), ::testing::HasSubstr("--profile 'scna=x'"));
}

}  // namespace
}  // namespace uavslam
