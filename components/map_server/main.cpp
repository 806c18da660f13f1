// map_server: subscribes `map_points` (and `pose`, for its status), keeps the world point map and
// an OctoMap occupancy octree (each keyframe ray-cast from its sensor origin), and publishes `map`
// snapshots (pruned, maximum likelihood) at most once per publish period and only when the map
// changed. The `map` writer is TRANSIENT_LOCAL, so a ground station joining late gets the current
// map. On stop it can write the octree (`map.bt`) and every received point (`map_points.ply`).
// With the matcher's back end, `keyframe_poses` moves the keyframes after a loop: each keyframe's
// points go from the pose they were published with to the corrected one and the octree is
// rebuilt from them.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>

#include <msg/KeyframePosesPubSubTypes.h>
#include <msg/MapPointsPubSubTypes.h>
#include <msg/OccupancyMapPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <CLI/CLI.hpp>

#include "backend/KeyframeGraph.hpp"
#include "common/HandoffQueue.hpp"
#include "common/IncompatibleQos.hpp"
#include "common/NodeOptions.hpp"
#include "common/RunNode.hpp"
#include "common/StopRequest.hpp"
#include "dds/Conversions.hpp"
#include "dds/MatcherMessages.hpp"
#include "dds/OccupancyMapConversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "io/FileError.hpp"
#include "io/OctreeFile.hpp"
#include "io/PlyFile.hpp"
#include "maps/OccupancyOctree.hpp"

namespace uavslam {
namespace {
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

struct MapServerOptions {
  OccupancyConfig occupancy;
  double publish_period = 1.0;  // s
  std::string out;              // empty: write no files on stop
};

// Mean and maximum of a duration in milliseconds.
struct TimeFigure {
  std::uint64_t count = 0;
  double total_ms = 0.0;
  double max_ms = 0.0;
  void add(Clock::time_point start) {
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    ++count;
    total_ms += ms;
    max_ms = std::max(max_ms, ms);
  }
  double mean_ms() const { return count ? total_ms / count : 0.0; }
};

// A malformed configuration is a configuration error (exit 2), whichever path set the value.
OccupancyOctree make_octree(const OccupancyConfig& config) {
  try {
    return OccupancyOctree(config);
  } catch (const std::invalid_argument& e) {
    throw io::ConfigError(std::string("bad occupancy setting (flag or config key): ") + e.what());
  }
}

void prepare_out_dir(const std::string& out) {
  if (out.empty()) return;
  std::error_code error;
  fs::create_directories(out, error);
  if (error) throw io::file_error(out, "cannot create the output directory: " + error.message());
}

class MapServerNode {
 public:
  MapServerNode(const process::NodeOptions& node, const MapServerOptions& o)
      : vehicle_(node.vehicle),
        options_(o),
        octree_(make_octree(o.occupancy)),
        participant_(node.domain, process::profiles_path(node), node.participant_profile,
                     "map_server"),
        map_(participant_, dds::topic_name(vehicle_, dds::kMapTopic),
             node.profile(dds::kMapTopic, "map_writer")),
        map_points_(participant_, dds::topic_name(vehicle_, dds::kMapPointsTopic),
                    node.profile(dds::kMapPointsTopic, "map_points_reader"),
                    [this](const msg::MapPoints& m, const eprosima::fastdds::dds::SampleInfo&) {
                      queue_.push(m);
                    }),
        keyframe_poses_(
            participant_, dds::topic_name(vehicle_, dds::kKeyframePosesTopic),
            node.profile(dds::kKeyframePosesTopic, "map_reader"),
            [this](const msg::KeyframePoses& m, const eprosima::fastdds::dds::SampleInfo&) {
              // Each holds every keyframe: only the newest matters.
              std::lock_guard<std::mutex> lock(correction_mutex_);
              correction_ = m;
            }),
        poses_(participant_, dds::topic_name(vehicle_, dds::kPoseTopic),
               node.profile(dds::kPoseTopic, "state_reader"),
               [this](const msg::PoseWithCovarianceStamped& m,
                      const eprosima::fastdds::dds::SampleInfo&) {
                 std::lock_guard<std::mutex> lock(pose_mutex_);
                 last_pose_ = dds::from_msg(m);
               }) {}

  int run() {
    std::cerr << "map_server: mapping " << map_points_.topic() << " into " << map_.topic() << " at "
              << options_.occupancy.resolution << " m\n";
    const auto period = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(options_.publish_period));
    auto last_publish = Clock::now() - period;
    while (!process::stop_requested()) {
      check_qos();
      ingest_queued(std::chrono::milliseconds(100));
      apply_correction();
      if (map_changed() && Clock::now() - last_publish >= period) {
        last_publish = Clock::now();
        publish_snapshot();
      }
    }
    flush();
    // OctoMap's own progress output on writing goes before our summary line.
    if (!options_.out.empty()) write_files();
    print_summary();
    return qos_.exit_code();
  }

 private:
  void check_qos() {
    qos_.input(map_points_);
    qos_.input(keyframe_poses_);
    qos_.input(poses_);
    qos_.output(map_);
  }

  // Every keyframe the DDS thread queued, waiting up to `timeout` for the first.
  void ingest_queued(std::chrono::milliseconds timeout) {
    queue_.take_all(batch_, timeout);
    for (const msg::MapPoints& m : batch_) ingest(m);
  }

  void ingest(const msg::MapPoints& m) {
    Keyframe keyframe{dds::from_msg(m),
                      dds::from_msg(m.sensor_origin()),
                      {dds::from_msg(m.body_position()), m.body_yaw()}};
    if (!is_well_formed_keyframe(keyframe.points, keyframe.origin)) {
      ++malformed_;
      return;
    }
    // A keyframe delivered again (a TRANSIENT_LOCAL history replayed to us) must not count its
    // points twice.
    if (keyframes_.count(m.keyframe_index()) != 0) {
      ++duplicates_;
      return;
    }
    // A correction that came before it (the topics are not ordered with each other) moves it.
    const auto corrected = corrected_poses_.find(m.keyframe_index());
    if (corrected != corrected_poses_.end()) move(keyframe, corrected->second);
    const auto start = Clock::now();
    octree_.insert_keyframe(keyframe.points, keyframe.origin);
    insert_time_.add(start);
    world_points_.insert(world_points_.end(), keyframe.points.begin(), keyframe.points.end());
    last_stamp_ = dds::from_msg_time(m.header().stamp());
    keyframes_.emplace(m.keyframe_index(), std::move(keyframe));
  }

  // The newest correction, if one came: every keyframe it names moved to its pose, the octree
  // and the point list rebuilt from all of them.
  void apply_correction() {
    std::optional<msg::KeyframePoses> correction;
    {
      std::lock_guard<std::mutex> lock(correction_mutex_);
      correction.swap(correction_);
    }
    if (!correction) return;
    const auto start = Clock::now();
    for (const dds::KeyframePlacement& placed : dds::from_msg(*correction)) {
      corrected_poses_[placed.index] = placed.pose;
      const auto stored = keyframes_.find(placed.index);
      if (stored != keyframes_.end()) move(stored->second, placed.pose);
    }
    octree_ = make_octree(options_.occupancy);
    world_points_.clear();
    for (const auto& [index, keyframe] : keyframes_) {
      octree_.insert_keyframe(keyframe.points, keyframe.origin);
      world_points_.insert(world_points_.end(), keyframe.points.begin(), keyframe.points.end());
    }
    ++corrections_;
    rebuild_time_.add(start);
  }

  struct Keyframe {
    Points points;
    Vec3 origin;
    backend::NodePose body;  // where the points were placed from
  };

  static void move(Keyframe& keyframe, const backend::NodePose& to) {
    const backend::MapCorrection c = backend::correction_between(keyframe.body, to);
    for (Vec3& p : keyframe.points) p = c.transform * p;
    keyframe.origin = c.transform * keyframe.origin;
    keyframe.body = to;
  }

  bool map_changed() const {
    return octree_.revision() != published_revision_ || corrections_ != published_corrections_;
  }

  void publish_snapshot() {
    const auto start = Clock::now();
    const msg::OccupancyMap snapshot =
        dds::to_msg(octree_.pruned_tree(), publish_time_.count, octree_.points_inserted(),
                    last_stamp_, dds::Source{"map", vehicle_});
    if (!map_.write(snapshot)) {
      std::cerr << "map_server: snapshot " << publish_time_.count << " not accepted by DDS\n";
      return;
    }
    publish_time_.add(start);
    published_revision_ = octree_.revision();
    published_corrections_ = corrections_;
    last_snapshot_bytes_ = snapshot.octomap_binary().size();
  }

  // On stop: what is still queued goes into the map, the map out to its subscribers.
  void flush() {
    ingest_queued(std::chrono::milliseconds(0));
    if (map_changed()) publish_snapshot();
    // The writer is asynchronous: give the last snapshot a moment to reach its readers.
    if (map_.matched() > 0) map_.wait_for_acknowledgments(std::chrono::seconds(2));
  }

  void write_files() const {
    io::write_bt((fs::path(options_.out) / "map.bt").string(), octree_.tree());
    io::write_ply((fs::path(options_.out) / "map_points.ply").string(), world_points_);
  }

  void print_summary() {
    std::lock_guard<std::mutex> lock(pose_mutex_);
    std::cerr << "map_server: " << octree_.keyframes_inserted() << " keyframes, "
              << octree_.points_inserted() << " points, " << octree_.occupied_leaves()
              << " occupied cells (insert " << insert_time_.mean_ms() << " ms mean, "
              << insert_time_.max_ms << " ms max); " << publish_time_.count
              << " snapshots published (last " << last_snapshot_bytes_ << " bytes, "
              << publish_time_.mean_ms() << " ms mean, " << publish_time_.max_ms
              << " ms max); dropped " << duplicates_ << " duplicate and " << malformed_
              << " malformed keyframes; " << corrections_
              << " corrections from the back end applied (rebuild " << rebuild_time_.mean_ms()
              << " ms mean); " << poses_.received() << " poses seen";
    if (poses_.received() > 0) {
      const Vec3& p = last_pose_.position;
      std::cerr << " (last at " << p.x() << ", " << p.y() << ", " << p.z() << ")";
    }
    std::cerr << "\n";
  }

  std::string vehicle_;
  MapServerOptions options_;
  OccupancyOctree octree_;
  Points world_points_;
  std::map<std::uint32_t, Keyframe> keyframes_;                 // by index, as last placed
  std::map<std::uint32_t, backend::NodePose> corrected_poses_;  // the newest correction's
  std::mutex correction_mutex_;
  std::optional<msg::KeyframePoses> correction_;  // received, not applied yet
  std::uint64_t corrections_ = 0;
  std::uint64_t published_corrections_ = 0;
  TimeFigure rebuild_time_;
  std::uint64_t duplicates_ = 0;
  std::uint64_t malformed_ = 0;
  std::uint64_t published_revision_ = 0;
  double last_stamp_ = 0.0;
  TimeFigure insert_time_;
  TimeFigure publish_time_;  // encoding a snapshot and handing it to DDS
  std::size_t last_snapshot_bytes_ = 0;
  std::mutex pose_mutex_;
  Pose last_pose_;
  // Unbounded: no keyframe may be lost (each carries points no later one repeats).
  process::HandoffQueue<msg::MapPoints> queue_;
  std::vector<msg::MapPoints> batch_;
  process::QosWatch qos_{"map_server"};
  dds::Participant participant_;
  dds::Writer<msg::OccupancyMapPubSubType> map_;
  dds::Reader<msg::MapPointsPubSubType> map_points_;
  dds::Reader<msg::KeyframePosesPubSubType> keyframe_poses_;
  dds::Reader<msg::PoseWithCovarianceStampedPubSubType> poses_;
};

void apply_own_config(const CLI::App& app, const io::YamlReader& section, MapServerOptions& o) {
  section.expect_keys_only(
      {"resolution", "max_range", "publish_period", "out", "probability_hit", "probability_miss"});
  OccupancyConfig& c = o.occupancy;
  if (process::unset(app, "--resolution")) {
    c.resolution = section.get_double_or("resolution", c.resolution, io::NumberRange::positive());
  }
  if (process::unset(app, "--max-range")) {
    c.max_range = section.get_double_or("max_range", c.max_range, io::NumberRange::positive());
  }
  if (process::unset(app, "--publish-period")) {
    o.publish_period =
        section.get_double_or("publish_period", o.publish_period, io::NumberRange::non_negative());
  }
  if (process::unset(app, "--out")) o.out = section.get_string_or("out", o.out);
  if (process::unset(app, "--probability-hit")) {
    c.probability_hit = section.get_double_or("probability_hit", c.probability_hit,
                                              io::NumberRange::greater_than(0.5));
  }
  if (process::unset(app, "--probability-miss")) {
    c.probability_miss =
        section.get_double_or("probability_miss", c.probability_miss, io::NumberRange::positive());
  }
}

void add_own_options(CLI::App& app, MapServerOptions& o) {
  app.add_option("--resolution", o.occupancy.resolution, "octree leaf size (m)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--max-range", o.occupancy.max_range,
                 "longest ray marked (m): a farther point clears its ray up to here and marks "
                 "nothing (default: no limit)")
      ->check(CLI::PositiveNumber);
  app.add_option(
         "--publish-period", o.publish_period,
         "least time between two `map` snapshots (s); one is sent only when the map changed")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--out", o.out, "on stop, write map.bt (OctoMap) and map_points.ply here");
  app.add_option("--probability-hit", o.occupancy.probability_hit,
                 "occupancy probability a ray's end adds, in (0.5, 1)")
      ->capture_default_str();
  app.add_option("--probability-miss", o.occupancy.probability_miss,
                 "occupancy probability a ray's crossing adds, in (0, 0.5)")
      ->capture_default_str();
}

}  // namespace
}  // namespace uavslam

int main(int argc, char** argv) {
  CLI::App app{
      "map_server: subscribes map_points (and pose), keeps an OctoMap occupancy map, publishes "
      "map snapshots (late joiners get the current one)"};
  uavslam::process::NodeOptions node;
  uavslam::MapServerOptions options;
  uavslam::process::add_node_options(app, node);
  uavslam::add_own_options(app, options);
  if (const auto code = uavslam::process::parse_command_line(app, argc, argv)) return *code;
  uavslam::process::install_stop_handler();
  return uavslam::process::run_node("map_server", [&] {
    if (const auto section = uavslam::process::apply_node_config(app, node, "map_server")) {
      uavslam::apply_own_config(app, *section, options);
    }
    uavslam::prepare_out_dir(options.out);
    uavslam::MapServerNode server(node, options);
    return server.run();
  });
}
