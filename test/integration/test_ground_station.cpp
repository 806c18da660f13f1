// The ground_station process as a late joiner: the test plays the vehicle side with real DDS
// writers (map snapshot and matcher status first, then poses and scans), starts the real process
// afterwards, stops it with SIGTERM and checks every file it wrote.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/OccupancyMapPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <octomap/OcTree.h>
#include <nlohmann/json.hpp>

#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"
#include "dds/Conversions.hpp"
#include "dds/OccupancyMapConversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "io/OctreeFile.hpp"
#include "io/PlyFile.hpp"
#include "io/PngFile.hpp"
#include "io/TumFile.hpp"

namespace uavslam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using ::testing::HasSubstr;
using ReturnCode_t = eprosima::fastrtps::types::ReturnCode_t;

// This test's own DDS domains, one per test so they cannot hear each other.
constexpr int kLateJoinDomain = 175;
constexpr int kBadMapDomain = 176;
constexpr int kIncompatibleDomain = 177;
constexpr char kVehicle[] = "uav1";
const eprosima::fastrtps::Duration_t kAckTimeout(30, 0);
const dds::Source kSource{"map", kVehicle};

class GroundStationTest : public test::ProcessTest {
 protected:
  std::vector<std::string> station(int domain, std::vector<std::string> extra = {}) const {
    extra.insert(extra.begin(),
                 {"--vehicle", kVehicle, "--out", path("out"), "--status-period", "0.2"});
    return node_argv("ground_station", domain, extra);
  }
  fs::path out(const char* name) const { return dir / "out" / name; }
  nlohmann::json summary() const {
    std::ifstream in(out("summary.json"));
    return nlohmann::json::parse(in);
  }
};

template <typename PubSubType>
dds::Writer<PubSubType> writer(dds::Participant& p, const char* topic, const char* profile) {
  return dds::Writer<PubSubType>(p, dds::topic_name(kVehicle, topic), profile);
}

// A wall at x = 2.05 m, 1 m long and 1 m high (10 x 10 cells of 0.1 m), and free space before it.
octomap::OcTree wall_map() {
  octomap::OcTree tree(0.1);
  for (int j = 0; j < 10; ++j) {
    for (int k = 0; k < 10; ++k) {
      tree.updateNode(2.05, 0.05 + 0.1 * j, 0.05 + 0.1 * k, true);
      for (int i = 0; i < 20; ++i)
        tree.updateNode(0.05 + 0.1 * i, 0.05 + 0.1 * j, 0.05 + 0.1 * k, false);
    }
  }
  tree.updateInnerOccupancy();
  tree.prune();
  return tree;
}

msg::MatcherStatus matcher_status() {
  msg::MatcherStatus status;
  msg::Header header;
  header.seq(41);  // the 42nd scan processed
  header.vehicle_id(kVehicle);
  status.header(header);
  status.outcome("accepted");
  status.scans_received(50);
  status.scans_skipped(2);
  status.scans_rejected(3);
  status.scans_accepted(39);
  status.tracking("degraded");
  status.tracking_reason("degenerate");
  return status;
}

msg::LaserScan scan(std::uint64_t seq) {
  msg::LaserScan m;
  msg::Header header;
  header.seq(seq);
  header.vehicle_id(kVehicle);
  m.header(header);
  m.ranges(std::vector<float>(16, 2.0f));
  return m;
}

Pose pose(std::uint64_t i) {
  Pose p;
  p.stamp = 100.0 + 0.025 * static_cast<double>(i);
  p.position = {0.1 * static_cast<double>(i), 0.5, 1.0};
  return p;
}

TEST_F(GroundStationTest, LateJoinerGetsTheMapAndRecordsTheFlight) {
  constexpr std::uint64_t kPoses = 20;
  dds::Participant vehicle(kLateJoinDomain, dds::default_profiles_path(), "uavslam_loopback",
                           "test_vehicle");
  auto map_writer = writer<msg::OccupancyMapPubSubType>(vehicle, dds::kMapTopic, "map_writer");
  auto status_writer =
      writer<msg::MatcherStatusPubSubType>(vehicle, dds::kMatcherStatusTopic, "status_writer");
  auto pose_writer =
      writer<msg::PoseWithCovarianceStampedPubSubType>(vehicle, dds::kPoseTopic, "state_writer");
  auto scan_writer = writer<msg::LaserScanPubSubType>(vehicle, dds::kScanTopic, "sensor_writer");

  const octomap::OcTree tree = wall_map();
  const std::size_t occupied = io::occupied_cell_centres(tree).size();
  ASSERT_EQ(occupied, 100u);
  const msg::OccupancyMap snapshot = dds::to_msg(tree, 7, 1234, 99.0, kSource);
  ASSERT_TRUE(map_writer.write(snapshot));
  ASSERT_TRUE(status_writer.write(matcher_status()));

  process::ChildProcess gcs(station(kLateJoinDomain), log_path("ground_station"));
  ASSERT_TRUE(gcs.started());
  ASSERT_TRUE(map_writer.wait_for_matched(1, 30s)) << gcs.log();
  ASSERT_TRUE(status_writer.wait_for_matched(1, 30s)) << gcs.log();
  ASSERT_TRUE(pose_writer.wait_for_matched(1, 30s)) << gcs.log();
  ASSERT_TRUE(scan_writer.wait_for_matched(1, 30s)) << gcs.log();
  // The samples written before the station existed reach it (TRANSIENT_LOCAL).
  ASSERT_EQ(map_writer.native().wait_for_acknowledgments(kAckTimeout), ReturnCode_t::RETCODE_OK);
  ASSERT_EQ(status_writer.native().wait_for_acknowledgments(kAckTimeout), ReturnCode_t::RETCODE_OK);

  for (std::uint64_t i = 0; i < kPoses; ++i) {
    ASSERT_TRUE(scan_writer.write(scan(i)));
    ASSERT_TRUE(pose_writer.write(dds::to_msg(pose(i), 1.0f, i, i, kSource)));
    // One at a time: the state profile keeps only the last 10 unacknowledged poses.
    ASSERT_EQ(pose_writer.native().wait_for_acknowledgments(kAckTimeout), ReturnCode_t::RETCODE_OK);
  }
  ASSERT_EQ(gcs.stop(10s), 0) << gcs.log();
  EXPECT_THAT(gcs.log(), HasSubstr("(snapshot 7)"));
  EXPECT_THAT(gcs.log(), HasSubstr("degraded (degenerate), accepted 39 rejected 3 skipped 2"));

  const std::vector<Pose> trajectory = io::read_tum(out("trajectory.tum").string());
  ASSERT_EQ(trajectory.size(), kPoses);
  for (std::uint64_t i = 0; i < kPoses; ++i) {
    EXPECT_NEAR((trajectory[i].position - pose(i).position).norm(), 0.0, 1e-6) << i;
    EXPECT_NEAR(trajectory[i].stamp, pose(i).stamp, 1e-6) << i;
  }
  // When each pose arrived: one line per pose, in arrival order, on the system clock.
  std::ifstream arrivals(out("pose_arrivals.csv"));
  std::string line;
  std::getline(arrivals, line);
  EXPECT_EQ(line, "scan_seq,stamp,received_at,latency_ms");
  const double now =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  std::uint64_t rows = 0;
  double previous = 0.0;
  while (std::getline(arrivals, line)) {
    unsigned long long seq = 0;
    double stamp = 0.0, received_at = 0.0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%llu,%lf,%lf", &seq, &stamp, &received_at), 3) << line;
    EXPECT_EQ(seq, rows);
    EXPECT_NEAR(stamp, pose(rows).stamp, 1e-6);
    EXPECT_GE(received_at, previous);
    EXPECT_LT(now - received_at, 120.0);
    previous = received_at;
    ++rows;
  }
  EXPECT_EQ(rows, kPoses);

  const auto map = io::read_bt(out("map.bt").string());
  EXPECT_EQ(io::occupied_cell_centres(*map).size(), occupied);
  const octomap::OcTreeNode* wall_cell = map->search(2.05, 0.55, 0.55);
  ASSERT_NE(wall_cell, nullptr);
  EXPECT_TRUE(map->isNodeOccupied(wall_cell));
  EXPECT_EQ(io::read_ply(out("map_occupied.ply").string()).size(), occupied);

  std::ifstream png(out("map_topdown.png"), std::ios::binary);
  std::string signature(8, '\0');
  png.read(signature.data(), 8);
  EXPECT_EQ(signature, "\x89PNG\r\n\x1a\n");
  const io::RgbImage picture = io::read_png(out("map_topdown.png").string());

  const nlohmann::json s = summary();
  EXPECT_EQ(s["poses"]["received"], kPoses);
  EXPECT_EQ(s["poses"]["malformed"], 0);
  EXPECT_EQ(s["map"]["snapshots_received"], 1);
  EXPECT_EQ(s["map"]["malformed"], 0);
  EXPECT_EQ(s["map"]["last_map_seq"], 7);
  EXPECT_EQ(s["map"]["map_points"], 1234);
  EXPECT_EQ(s["map"]["occupied_cells"], snapshot.occupied_cells());
  EXPECT_EQ(s["matcher_status"]["scans_received"], 50);
  EXPECT_EQ(s["matcher_status"]["scans_accepted"], 39);
  EXPECT_EQ(s["map_topdown"]["width_px"], picture.width());
  EXPECT_EQ(s["map_topdown"]["height_px"], picture.height());
  // Scans are BEST_EFFORT, so one may be lost; every pose whose scan arrived has a latency.
  const auto latencies = s["latency_scan_to_pose"]["count"].get<std::uint64_t>();
  EXPECT_GE(latencies, 1u);
  EXPECT_LE(latencies, kPoses);
  EXPECT_GE(s["latency_scan_to_pose"]["p50_ms"].get<double>(), 0.0);
  std::cerr << "ground station: " << gcs.log() << "summary: " << s.dump() << "\n";
}

TEST_F(GroundStationTest, ABadMapIsCountedAndNothingElseStillWritesTheOutputs) {
  dds::Participant vehicle(kBadMapDomain, dds::default_profiles_path(), "uavslam_loopback",
                           "test_vehicle");
  auto map_writer = writer<msg::OccupancyMapPubSubType>(vehicle, dds::kMapTopic, "map_writer");
  msg::OccupancyMap bad = dds::to_msg(wall_map(), 3, 10, 99.0, kSource);
  bad.octomap_binary(std::vector<std::uint8_t>(64, 0x5a));
  ASSERT_TRUE(map_writer.write(bad));

  process::ChildProcess gcs(station(kBadMapDomain), log_path("ground_station"));
  ASSERT_TRUE(gcs.started());
  ASSERT_TRUE(map_writer.wait_for_matched(1, 30s)) << gcs.log();
  ASSERT_EQ(map_writer.native().wait_for_acknowledgments(kAckTimeout), ReturnCode_t::RETCODE_OK);
  ASSERT_EQ(gcs.stop(10s), 0) << gcs.log();
  EXPECT_THAT(gcs.log(), HasSubstr("dropped a map snapshot: map snapshot 3"));

  EXPECT_TRUE(io::read_tum(out("trajectory.tum").string()).empty());
  EXPECT_FALSE(fs::exists(out("map.bt")));
  EXPECT_FALSE(fs::exists(out("map_topdown.png")));
  const nlohmann::json s = summary();
  EXPECT_EQ(s["poses"]["received"], 0);
  EXPECT_EQ(s["map"]["snapshots_received"], 0);
  EXPECT_EQ(s["map"]["malformed"], 1);
  EXPECT_EQ(s["latency_scan_to_pose"]["count"], 0);
}

TEST_F(GroundStationTest, AnIncompatiblePeerStopsItNamingTopicAndPolicy) {
  dds::Participant vehicle(kIncompatibleDomain, dds::default_profiles_path(), "uavslam_loopback",
                           "test_vehicle");
  // A best-effort pose writer cannot serve the station's reliable pose reader.
  auto wrong =
      writer<msg::PoseWithCovarianceStampedPubSubType>(vehicle, dds::kPoseTopic, "sensor_writer");
  process::ChildProcess gcs(station(kIncompatibleDomain), log_path("ground_station"));
  ASSERT_TRUE(gcs.started());
  ASSERT_TRUE(gcs.wait(30s)) << gcs.log();
  EXPECT_EQ(gcs.exit_code(), 1) << gcs.log();
  EXPECT_THAT(gcs.log(), HasSubstr("uav1/pose"));
  EXPECT_THAT(gcs.log(), HasSubstr("RELIABILITY"));
  EXPECT_TRUE(fs::exists(out("summary.json"))) << "what was received is still written";
}

TEST_F(GroundStationTest, AnUnknownConfigKeyIsAConfigError) {
  const std::string config = path("gcs.yaml");
  std::ofstream(config) << "ground_station:\n  status_perod: 2\n";
  process::ChildProcess gcs(station(kIncompatibleDomain, {"--config", config}),
                            log_path("ground_station"));
  ASSERT_TRUE(gcs.wait(30s)) << gcs.log();
  EXPECT_EQ(gcs.exit_code(), 2);
  EXPECT_THAT(gcs.log(), HasSubstr("status_perod"));
}

}  // namespace
}  // namespace uavslam
