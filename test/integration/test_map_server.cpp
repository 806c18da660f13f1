// The map server as a real process on its own DDS domain: the test publishes synthetic keyframes
// (the walls of a box room seen from inside) and reads the `map` snapshots, one reader early and
// one joining late.
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <msg/KeyframePosesPubSubTypes.h>
#include <msg/MapPointsPubSubTypes.h>
#include <msg/OccupancyMapPubSubTypes.h>

#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"
#include "dds/Conversions.hpp"
#include "dds/MatcherMessages.hpp"
#include "dds/OccupancyMapConversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "io/PlyFile.hpp"

namespace uavslam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr int kMapDomain = 110;  // this test's own DDS domains (172 was test_mcap_replay's too)
constexpr int kConfigDomain = 173;
constexpr int kIncompatibleDomain = 174;
constexpr int kCorrectionDomain = 103;

// Room walls at x = +-2.05 and y = +-2.05 (cell centres of the 0.1 m grid), 0.05 .. 1.95 m high.
// The sensor sits at the centre, 1.05 m up.
const Vec3 kOrigin{0.05, 0.05, 1.05};

Points wall(int axis, double at) {
  Points points;
  for (int i = -19; i <= 19; ++i) {
    for (int k = 0; k < 10; ++k) {
      Vec3 p(0.05 + 0.1 * i, 0.05 + 0.1 * i, 0.05 + 0.2 * k);
      p[axis] = at;
      points.push_back(p);
    }
  }
  return points;
}

std::vector<Points> room_walls() {
  return {wall(0, 2.05), wall(0, -1.95), wall(1, 2.05), wall(1, -1.95)};
}

// Every keyframe made at the room's centre, heading along x.
msg::MapPoints keyframe(const Points& points, std::uint32_t index) {
  Pose body;
  body.stamp = 100.0 + index;
  body.position = kOrigin - Vec3(0.0, 0.0, 0.1);
  return dds::to_msg(points, kOrigin, body, index, dds::Source{"map", "uav1"});
}

bool occupied(const octomap::OcTree& tree, const Vec3& p) {
  const octomap::OcTreeNode* node = tree.search(p.x(), p.y(), p.z());
  return node != nullptr && tree.isNodeOccupied(node);
}

bool free_space(const octomap::OcTree& tree, const Vec3& p) {
  const octomap::OcTreeNode* node = tree.search(p.x(), p.y(), p.z());
  return node != nullptr && !tree.isNodeOccupied(node);
}

// The newest snapshot a map reader has received, and waiting for one that holds `points`.
class SnapshotInbox {
 public:
  void put(const msg::OccupancyMap& m) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      latest_ = m;
    }
    changed_.notify_all();
  }
  std::optional<msg::OccupancyMap> wait_for_points(std::uint64_t points,
                                                   std::chrono::seconds timeout) {
    return wait_for([&](const msg::OccupancyMap& m) { return m.map_points() >= points; }, timeout);
  }
  // The newest snapshot once one satisfies `holds` (or the newest at the timeout).
  template <typename Predicate>
  std::optional<msg::OccupancyMap> wait_for(Predicate holds, std::chrono::seconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return latest_ && holds(*latest_); });
    return latest_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<msg::OccupancyMap> latest_;
};

class MapServerProcess : public test::ProcessTest {
 protected:
  static std::vector<std::string> map_server(int domain, std::vector<std::string> extra) {
    extra.insert(extra.begin(), {"--vehicle", "uav1"});
    return node_argv("map_server", domain, extra);
  }
};

TEST_F(MapServerProcess, ALateJoinerGetsTheCurrentMapAndDuplicatesAreIgnored) {
  dds::Participant ground(kMapDomain, dds::default_profiles_path(), "uavslam_loopback", "test");
  dds::Writer<msg::MapPointsPubSubType> keyframes(
      ground, dds::topic_name("uav1", dds::kMapPointsTopic), "map_points_writer");
  SnapshotInbox early_inbox;
  dds::Reader<msg::OccupancyMapPubSubType> early(
      ground, dds::topic_name("uav1", dds::kMapTopic), "map_reader",
      [&](const msg::OccupancyMap& m, const eprosima::fastdds::dds::SampleInfo&) {
        early_inbox.put(m);
      });

  // The walls go out before the map server exists: it must get them from the writer's
  // TRANSIENT_LOCAL history, as from a matcher that started first.
  const std::vector<Points> walls = room_walls();
  std::uint64_t wall_points = 0;
  for (std::uint32_t i = 0; i < walls.size(); ++i) {
    ASSERT_TRUE(keyframes.write(keyframe(walls[i], i)));
    wall_points += walls[i].size();
  }
  const fs::path out = dir / "out";
  process::ChildProcess server(
      map_server(kMapDomain, {"--publish-period", "0.2", "--out", out.string()}),
      log_path("map_server"));
  ASSERT_TRUE(server.started());
  ASSERT_TRUE(keyframes.wait_for_matched(1, 30s)) << server.log();
  ASSERT_TRUE(early.wait_for_matched(1, 30s)) << server.log();
  ASSERT_TRUE(early_inbox.wait_for_points(wall_points, 30s)) << server.log();

  // Created only now: the snapshot it receives was published before it existed.
  SnapshotInbox late_inbox;
  dds::Reader<msg::OccupancyMapPubSubType> late(
      ground, dds::topic_name("uav1", dds::kMapTopic), "map_reader",
      [&](const msg::OccupancyMap& m, const eprosima::fastdds::dds::SampleInfo&) {
        late_inbox.put(m);
      });
  ASSERT_TRUE(late.wait_for_received(1, 30s)) << server.log();
  const auto snapshot = late_inbox.wait_for_points(wall_points, 0s);
  ASSERT_TRUE(snapshot);
  EXPECT_EQ(snapshot->map_points(), wall_points);
  EXPECT_DOUBLE_EQ(snapshot->resolution(), 0.1);
  const auto tree = dds::octree_from_msg(*snapshot);
  EXPECT_EQ(snapshot->occupied_cells(), wall_points) << "one cell per wall point";
  for (const Vec3& p : {Vec3(2.05, 0.05, 1.05), Vec3(-1.95, 1.05, 0.45), Vec3(0.55, 2.05, 1.85),
                        Vec3(-0.95, -1.95, 0.05)}) {
    EXPECT_TRUE(occupied(*tree, p)) << p.transpose();
  }
  // Cells on the level rays to the walls' middle row.
  for (const Vec3& p : {Vec3(1.05, 0.05, 1.05), Vec3(0.05, -1.05, 1.05), Vec3(-1.05, 0.05, 1.05),
                        Vec3(0.05, 1.55, 1.05)}) {
    EXPECT_TRUE(free_space(*tree, p)) << p.transpose();
  }

  // Keyframe 0 again (with other points, so a wrong insert would show), two malformed ones, then
  // a new keyframe: once its points are in a snapshot, everything before it was handled.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vec3 interior(0.55, 0.55, 1.05);
  ASSERT_TRUE(keyframes.write(keyframe({interior}, 0)));
  ASSERT_TRUE(keyframes.write(keyframe({}, 10)));
  ASSERT_TRUE(keyframes.write(keyframe({Vec3(1.0, nan, 1.0)}, 11)));
  const Points floor_patch{{0.05, 0.05, -0.95}, {0.15, 0.05, -0.95}};
  ASSERT_TRUE(keyframes.write(keyframe(floor_patch, 4)));
  const auto after = early_inbox.wait_for_points(wall_points + floor_patch.size(), 30s);
  ASSERT_TRUE(after) << server.log();
  EXPECT_EQ(after->map_points(), wall_points + floor_patch.size());
  const auto tree_after = dds::octree_from_msg(*after);
  EXPECT_FALSE(occupied(*tree_after, interior)) << "the duplicate keyframe was inserted";
  EXPECT_TRUE(occupied(*tree_after, floor_patch[0]));

  EXPECT_EQ(server.stop(10s), 0) << server.log();
  EXPECT_THAT(server.log(),
              ::testing::HasSubstr("5 keyframes, " + std::to_string(wall_points + 2) + " points"));
  EXPECT_THAT(server.log(), ::testing::HasSubstr("dropped 1 duplicate and 2 malformed"));

  octomap::OcTree saved(0.1);
  std::ifstream bt(out / "map.bt", std::ios::binary);
  ASSERT_TRUE(saved.readBinary(bt)) << (out / "map.bt");
  EXPECT_TRUE(occupied(saved, Vec3(2.05, 0.05, 1.05)));
  EXPECT_TRUE(free_space(saved, Vec3(1.05, 0.05, 1.05)));
  EXPECT_EQ(io::read_ply((out / "map_points.ply").string()).size(), wall_points + 2);
}

// The matcher's back end closed a loop: `keyframe_poses` moves keyframe 0 (the wall at x = 2.05)
// half a metre along x, and names keyframe 7, which has not arrived yet. The map is rebuilt with
// the wall moved, and keyframe 7 is moved as it arrives (the two topics are not ordered).
TEST_F(MapServerProcess, TheBackEndsCorrectionMovesTheKeyframesAndTheMapIsRebuilt) {
  dds::Participant ground(kCorrectionDomain, dds::default_profiles_path(), "uavslam_loopback",
                          "test");
  dds::Writer<msg::MapPointsPubSubType> keyframes(
      ground, dds::topic_name("uav1", dds::kMapPointsTopic), "map_points_writer");
  dds::Writer<msg::KeyframePosesPubSubType> corrections(
      ground, dds::topic_name("uav1", dds::kKeyframePosesTopic), "map_writer");
  SnapshotInbox inbox;
  dds::Reader<msg::OccupancyMapPubSubType> maps(
      ground, dds::topic_name("uav1", dds::kMapTopic), "map_reader",
      [&](const msg::OccupancyMap& m, const eprosima::fastdds::dds::SampleInfo&) { inbox.put(m); });
  process::ChildProcess server(map_server(kCorrectionDomain, {"--publish-period", "0.2"}),
                               log_path("map_server"));
  ASSERT_TRUE(server.started());
  ASSERT_TRUE(keyframes.wait_for_matched(1, 30s)) << server.log();
  ASSERT_TRUE(corrections.wait_for_matched(1, 30s)) << server.log();
  ASSERT_TRUE(maps.wait_for_matched(1, 30s)) << server.log();

  const std::vector<Points> walls = room_walls();
  std::uint64_t wall_points = 0;
  for (std::uint32_t i = 0; i < walls.size(); ++i) {
    ASSERT_TRUE(keyframes.write(keyframe(walls[i], i)));
    wall_points += walls[i].size();
  }
  const Vec3 on_wall(2.05, 0.05, 1.05);
  const Vec3 moved_wall(2.55, 0.05, 1.05);
  const auto before = inbox.wait_for_points(wall_points, 30s);
  ASSERT_TRUE(before && before->map_points() == wall_points) << server.log();
  EXPECT_TRUE(occupied(*dds::octree_from_msg(*before), on_wall));

  const Vec3 body = kOrigin - Vec3(0.0, 0.0, 0.1);
  std::vector<backend::NodePose> poses(8, backend::NodePose{body, 0.0});
  poses[0].position += Vec3(0.5, 0.0, 0.0);
  poses[7].position += Vec3(0.0, -0.5, 0.0);
  ASSERT_TRUE(corrections.write(dds::keyframe_poses_message(poses, {}, 104.0, 1, {"map", "uav1"})));
  const auto after = inbox.wait_for(
      [&](const msg::OccupancyMap& m) { return occupied(*dds::octree_from_msg(m), moved_wall); },
      30s);
  ASSERT_TRUE(after) << server.log();
  const auto tree = dds::octree_from_msg(*after);
  EXPECT_TRUE(occupied(*tree, moved_wall)) << server.log();
  EXPECT_FALSE(occupied(*tree, on_wall));
  EXPECT_TRUE(occupied(*tree, Vec3(-1.95, 1.05, 0.45))) << "the other walls stay";
  EXPECT_EQ(after->map_points(), wall_points);

  const Points floor_patch{{0.05, 0.05, -0.95}, {0.15, 0.05, -0.95}};
  ASSERT_TRUE(keyframes.write(keyframe(floor_patch, 7)));
  const auto last = inbox.wait_for_points(wall_points + floor_patch.size(), 30s);
  ASSERT_TRUE(last && last->map_points() == wall_points + floor_patch.size()) << server.log();
  EXPECT_TRUE(occupied(*dds::octree_from_msg(*last), Vec3(0.05, -0.45, -0.95)));
  EXPECT_FALSE(occupied(*dds::octree_from_msg(*last), floor_patch[0]));

  EXPECT_EQ(server.stop(10s), 0) << server.log();
  EXPECT_THAT(server.log(), ::testing::HasSubstr("1 corrections from the back end applied"));
}

TEST_F(MapServerProcess, ABadConfigValueIsNamedAndRefused) {
  const std::string config = path("map_server.yaml");
  std::ofstream(config) << "map_server:\n  resolution: -0.5\n";
  process::ChildProcess bad_file(map_server(kConfigDomain, {"--config", config}),
                                 log_path("map_server"));
  ASSERT_TRUE(bad_file.wait(30s));
  EXPECT_EQ(bad_file.exit_code(), 2);
  EXPECT_THAT(bad_file.log(), ::testing::HasSubstr("map_server.resolution"));
  EXPECT_THAT(bad_file.log(), ::testing::HasSubstr("-0.5"));

  process::ChildProcess bad_flag(map_server(kConfigDomain, {"--probability-hit", "1.5"}),
                                 log_path("map_server"));
  ASSERT_TRUE(bad_flag.wait(30s));
  EXPECT_EQ(bad_flag.exit_code(), 2);
  EXPECT_THAT(bad_flag.log(), ::testing::HasSubstr("probability_hit"));
}

TEST_F(MapServerProcess, AnIncompatibleMapReaderIsReportedAndTheOthersStillServed) {
  dds::Participant ground(kIncompatibleDomain, dds::default_profiles_path(), "uavslam_loopback",
                          "test");
  process::ChildProcess server(map_server(kIncompatibleDomain, {}), log_path("map_server"));
  ASSERT_TRUE(server.started());
  // A reader asking for a 100 ms deadline the map writer does not offer.
  dds::Reader<msg::OccupancyMapPubSubType> wrong(
      ground, dds::topic_name("uav1", dds::kMapTopic), "state_reader",
      [](const msg::OccupancyMap&, const eprosima::fastdds::dds::SampleInfo&) {});
  ASSERT_TRUE(wrong.wait_for_incompatible_qos(1, 30s));
  ASSERT_TRUE(wait_for_log(server, "serving the readers that match", 30s)) << server.log();
  EXPECT_THAT(server.log(), ::testing::HasSubstr("incompatible QoS on topic 'uav1/map'"));
  EXPECT_THAT(server.log(), ::testing::HasSubstr("DEADLINE"));

  // A well-configured reader still gets the map.
  SnapshotInbox inbox;
  dds::Reader<msg::OccupancyMapPubSubType> right(
      ground, dds::topic_name("uav1", dds::kMapTopic), "map_reader",
      [&](const msg::OccupancyMap& m, const eprosima::fastdds::dds::SampleInfo&) { inbox.put(m); });
  dds::Writer<msg::MapPointsPubSubType> keyframes(
      ground, dds::topic_name("uav1", dds::kMapPointsTopic), "map_points_writer");
  ASSERT_TRUE(keyframes.wait_for_matched(1, 30s)) << server.log();
  const Points points = room_walls().front();
  ASSERT_TRUE(keyframes.write(keyframe(points, 0)));
  const auto snapshot = inbox.wait_for_points(points.size(), 30s);
  ASSERT_TRUE(snapshot.has_value()) << server.log();
  EXPECT_EQ(snapshot->map_points(), points.size());

  // The deployment error still shows in the exit code.
  EXPECT_EQ(server.stop(10s), 1) << server.log();
}

}  // namespace
}  // namespace uavslam
