// The whole system as users run it: `uavslam launch` starts the six processes of a launch file
// (ground station, map server, recorder, matcher, IMU bridge, LiDAR driver) on the test's own
// domain, the sensors fly the short scenario, the launcher stops everything in reverse order, and
// every output is checked; and a ground station that joins after the flight still gets the map
// from the real map server.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"
#include "eval/TrajectoryMetrics.hpp"
#include "io/McapListing.hpp"
#include "io/OctreeFile.hpp"
#include "io/PlyFile.hpp"
#include "io/TumFile.hpp"

namespace uavslam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr int kLaunchDomain = 188;    // the launched system
constexpr int kLateJoinDomain = 189;  // the late-joining ground station
const std::string kSource = UAVSLAM_SOURCE_DIR;
const std::string kScenario = kSource + "/config/scenarios/short.yaml";

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

using System = test::ProcessTest;

TEST_F(System, TheLauncherFliesTheSixProcessesAndEveryOutputIsWritten) {
  const std::string sensor =
      "[--scenario, " + kScenario + ", --rate, \"4\", --start-at, \"{start_at}\", ";
  std::ofstream(path("flight.yaml"))
      << "domain: " << kLaunchDomain << "\nvehicle: uav7\nlog_dir: " << path("logs")
      << "\nprocesses:\n"
      << "  - {name: ground_station, args: [--out, " << path("gcs") << "]}\n"
      << "  - {name: map_server, args: [--out, " << path("map") << "]}\n"
      << "  - {name: recorder, args: [--out, " << path("flight.mcap") << "]}\n"
      << "  - {name: slam_matcher, args: [--sensor, " << kScenario << ", --slam-config, " << kSource
      << "/config/slam.yaml]}\n"
      << "  - {name: imu_bridge, args: " << sensor << "--wait-for-subscribers, \"2\"]}\n"
      << "  - {name: lidar_driver, until_exit: true, args: " << sensor
      << "--wait-for-subscribers, \"3\", --groundtruth, " << path("groundtruth.tum") << "]}\n";

  process::ChildProcess launch({binary("uavslam"), "launch", path("flight.yaml")},
                               path("launch.log"));
  ASSERT_TRUE(launch.wait(120s)) << launch.log();
  ASSERT_EQ(launch.exit_code(), 0) << launch.log();
  // Every process ended cleanly, in reverse order of starting, the ground station last.
  const std::string log = launch.log();
  EXPECT_LT(log.find("launch: slam_matcher exit 0"), log.find("launch: map_server exit 0")) << log;
  EXPECT_LT(log.find("launch: map_server exit 0"), log.find("launch: ground_station exit 0"))
      << log;

  const std::vector<Pose> truth = io::read_tum(path("groundtruth.tum"));
  const std::vector<Pose> poses = io::read_tum(path("gcs/trajectory.tum"));
  EXPECT_EQ(truth.size(), 801u) << "every scan of the 20 s flight published";
  EXPECT_GE(poses.size(), 720u) << "of 801 scans, at the ground station";
  const eval::TrajectoryErrors errors = eval::compare_trajectories(poses, truth);
  EXPECT_LT(errors.ate_horizontal_rmse, 0.10);
  EXPECT_LT(errors.ate_vertical_rmse, 0.10);

  // The map server's final map reached the ground station.
  const nlohmann::json summary = read_json(path("gcs/summary.json"));
  EXPECT_GT(summary["map"]["snapshots_received"].get<int>(), 0);
  const auto station_map = io::read_bt(path("gcs/map.bt"));
  const auto server_map = io::read_bt(path("map/map.bt"));
  EXPECT_GT(server_map->getNumLeafNodes(), 1000u);
  EXPECT_EQ(summary["map"]["map_points"].get<std::size_t>(),
            io::read_ply(path("map/map_points.ply")).size());
  EXPECT_GT(summary["latency_scan_to_pose"]["count"].get<int>(), 0);
  EXPECT_TRUE(fs::exists(path("gcs/map_topdown.png")));

  // The recorder kept every sample the sensors published (loopback, nothing lost).
  const io::McapListing recording = io::list_mcap(path("flight_000.mcap"));
  EXPECT_TRUE(recording.report.complete) << recording.report.problem;
  EXPECT_EQ(io::messages_on(recording, "uav7/scan"), 801u);
  EXPECT_EQ(io::messages_on(recording, "uav7/imu"), 4001u);
}

TEST_F(System, AGroundStationJoiningAfterTheFlightGetsTheMap) {
  process::ChildProcess map_server(node_argv("map_server", kLateJoinDomain, {"--out", path("map")}),
                                   path("map_server.log"));
  process::ChildProcess matcher(node_argv("slam_matcher", kLateJoinDomain, {"--sensor", kScenario}),
                                path("matcher.log"));
  const std::string start_at = shared_start_time();
  process::ChildProcess imu(
      node_argv("imu_bridge", kLateJoinDomain, sensor_flags(kScenario, start_at)), path("imu.log"));
  process::ChildProcess lidar(
      node_argv("lidar_driver", kLateJoinDomain, sensor_flags(kScenario, start_at)),
      path("lidar.log"));
  ASSERT_TRUE(lidar.wait(60s)) << lidar.log();
  ASSERT_EQ(lidar.exit_code(), 0) << lidar.log();
  EXPECT_EQ(matcher.stop(10s), 0) << matcher.log();

  // The flight is over; now the ground station starts.
  process::ChildProcess station(
      node_argv("ground_station", kLateJoinDomain,
                {"--out", path("gcs"), "--no-latency", "--status-period", "0.2"}),
      path("gcs.log"));
  ASSERT_TRUE(wait_for_log(station, "(snapshot", 30s)) << station.log();
  EXPECT_EQ(station.stop(10s), 0) << station.log();
  EXPECT_EQ(map_server.stop(10s), 0) << map_server.log();

  const nlohmann::json summary = read_json(path("gcs/summary.json"));
  EXPECT_EQ(summary["map"]["snapshots_received"].get<int>(), 1) << "only the latest, once";
  // The snapshot it got is the map server's whole map: the same occupied cells.
  const auto station_map = io::read_bt(path("gcs/map.bt"));
  const auto server_map = io::read_bt(path("map/map.bt"));
  const std::size_t occupied = io::occupied_cell_centres(*server_map).size();
  EXPECT_GT(occupied, 1000u);
  EXPECT_EQ(io::occupied_cell_centres(*station_map).size(), occupied);
}

}  // namespace
}  // namespace uavslam
