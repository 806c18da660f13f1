// ground_station: subscribes a vehicle's `pose`, `map` and `matcher_status` (and `scan`, for the
// end-to-end latency; `keyframe_poses`, the back end's corrections), prints a live status line
// and, when stopped, writes the trajectory, the corrected keyframes, the map (.bt, occupied-cell
// PLY, top-down PNG with the flight path) and summary.json. It may join
// at any time: `map` and `matcher_status` are TRANSIENT_LOCAL, so it gets their latest samples.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>

#include <msg/KeyframePosesPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/OccupancyMapPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <CLI/CLI.hpp>

#include "FlightRecord.hpp"
#include "common/IncompatibleQos.hpp"
#include "common/NodeOptions.hpp"
#include "common/RunNode.hpp"
#include "common/StopRequest.hpp"
#include "dds/Conversions.hpp"
#include "dds/DdsError.hpp"
#include "dds/MatcherMessages.hpp"
#include "dds/OccupancyMapConversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "io/FileError.hpp"

namespace uavslam {
namespace {

using SampleInfo = eprosima::fastdds::dds::SampleInfo;

struct StationOptions {
  std::string out = "out/ground_station";
  bool latency = true;
  double status_period = 1.0;  // s
  bool quiet = false;
};

double system_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

double to_seconds(const eprosima::fastrtps::rtps::Time_t& t) {
  return t.seconds() + t.nanosec() * 1e-9;
}

bool well_formed(const msg::PoseWithCovarianceStamped& m) {
  const auto& p = m.position();
  const auto& q = m.orientation();
  const double norm = std::sqrt(q.x() * q.x() + q.y() * q.y() + q.z() * q.z() + q.w() * q.w());
  return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()) &&
         std::isfinite(norm) && norm > 1e-6;
}

// The matcher publishes one status per processed scan, numbered from 0, so header.seq + 1 scans
// were processed, and those not rejected were accepted.
ground_station::MatcherCounters counters_of(const msg::MatcherStatus& m) {
  ground_station::MatcherCounters c;
  c.scans_received = m.scans_received();
  c.scans_skipped = m.scans_skipped();
  c.scans_rejected = m.scans_rejected();
  c.scans_accepted = m.scans_accepted();
  c.last_outcome = m.outcome();
  c.tracking = m.tracking();
  c.tracking_reason = m.tracking_reason();
  c.loops_searched = m.loops_searched();
  c.loops_accepted = m.loops_accepted();
  c.corrections = m.corrections();
  c.heading_drift_deg_per_min = m.heading_drift_deg_per_min();
  return c;
}

class GroundStation {
 public:
  GroundStation(const process::NodeOptions& node, const StationOptions& options)
      : options_(options),
        node_(node),
        vehicle_(node.vehicle),
        participant_(node.domain, process::profiles_path(node), node.participant_profile,
                     "ground_station") {
    // An unwritable output directory is a configuration error: found now, not after the flight.
    std::error_code error;
    std::filesystem::create_directories(options_.out, error);
    if (error) throw io::file_error(options_.out, "cannot create directory: " + error.message());
    subscribe();
  }

  int run() {
    if (!options_.quiet) {
      std::cerr << "ground_station: listening to " << dds::topic_name(vehicle_, "")
                << "* on domain " << participant_.domain_id() << ", writing to " << options_.out
                << " on stop\n";
    }
    try {
      wait_for_stop();
    } catch (const process::IncompatibleQosError&) {
      finish();  // keep what was received, then report the deployment error
      throw;
    }
    finish();
    return 0;
  }

 private:
  void subscribe() {
    pose_ = std::make_unique<PoseReader>(
        participant_, dds::topic_name(vehicle_, dds::kPoseTopic),
        node_.profile(dds::kPoseTopic, "state_reader"),
        [this](const msg::PoseWithCovarianceStamped& m, const SampleInfo&) { on_pose(m); });
    map_ = std::make_unique<MapReader>(
        participant_, dds::topic_name(vehicle_, dds::kMapTopic),
        node_.profile(dds::kMapTopic, "map_reader"),
        [this](const msg::OccupancyMap& m, const SampleInfo&) { on_map(m); });
    keyframe_poses_ = std::make_unique<KeyframePosesReader>(
        participant_, dds::topic_name(vehicle_, dds::kKeyframePosesTopic),
        node_.profile(dds::kKeyframePosesTopic, "map_reader"),
        [this](const msg::KeyframePoses& m, const SampleInfo&) { on_keyframe_poses(m); });
    status_ = std::make_unique<StatusReader>(
        participant_, dds::topic_name(vehicle_, dds::kMatcherStatusTopic),
        node_.profile(dds::kMatcherStatusTopic, "status_reader"),
        [this](const msg::MatcherStatus& m, const SampleInfo&) {
          record_.set_matcher_status(counters_of(m));
        });
    if (options_.latency) {
      scans_ = std::make_unique<ScanReader>(
          participant_, dds::topic_name(vehicle_, dds::kScanTopic),
          node_.profile(dds::kScanTopic, "sensor_reader"),
          [this](const msg::LaserScan& m, const SampleInfo& info) {
            record_.add_scan(m.header().seq(), to_seconds(info.source_timestamp));
          });
    }
  }

  // Called on the pose reader's thread.
  void on_pose(const msg::PoseWithCovarianceStamped& m) {
    const double received_at = system_seconds();
    if (!well_formed(m)) {
      record_.add_malformed_pose();
      return;
    }
    record_.add_pose(dds::from_msg(m), m.scan_seq(), received_at);
  }

  // Called on the keyframe poses reader's thread.
  void on_keyframe_poses(const msg::KeyframePoses& m) {
    backend::StampedKeyframes correction;
    correction.stamp = dds::from_msg_time(m.header().stamp());
    for (const dds::KeyframePlacement& placed : dds::from_msg(m)) {
      correction.keyframes.push_back(backend::pose_of(placed.pose, placed.stamp));
    }
    record_.add_correction(std::move(correction));
  }

  // Called on the map reader's thread: decoding a large snapshot holds up only later snapshots.
  void on_map(const msg::OccupancyMap& m) {
    try {
      std::shared_ptr<const octomap::OcTree> tree = dds::octree_from_msg(m);
      record_.set_map(std::move(tree),
                      {m.map_seq(), m.map_points(), m.occupied_cells(), m.resolution()});
    } catch (const dds::DdsError& e) {
      record_.add_malformed_map();
      std::cerr << "ground_station: dropped a map snapshot: " << e.what() << "\n";
    }
  }

  void wait_for_stop() {
    using Clock = std::chrono::steady_clock;
    const auto period = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(options_.status_period));
    auto next_line = Clock::now() + period;
    while (!process::stop_requested()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      check_qos();
      if (Clock::now() < next_line) continue;
      next_line += period;
      const std::string line = record_.status_line();
      if (!options_.quiet) std::cerr << line << "\n";
    }
  }

  void check_qos() const {
    process::throw_if_incompatible(*pose_);
    process::throw_if_incompatible(*map_);
    process::throw_if_incompatible(*keyframe_poses_);
    process::throw_if_incompatible(*status_);
    if (scans_) process::throw_if_incompatible(*scans_);
  }

  // Stops receiving, so the files and the summary describe the same samples, then writes them.
  void finish() {
    scans_.reset();
    status_.reset();
    map_.reset();
    pose_.reset();
    const std::vector<std::string> files = record_.write_outputs(options_.out);
    if (options_.quiet) return;
    std::cerr << record_.status_line() << "\n";  // the last, partial period
    const nlohmann::json summary = record_.summary();
    const nlohmann::json& latency = summary["latency_scan_to_pose"];
    std::fprintf(stderr,
                 "ground_station: %zu poses, %zu map snapshots, latency p50 %.2f ms p99 %.2f ms "
                 "max %.2f ms over %zu poses; wrote",
                 summary["poses"]["received"].get<std::size_t>(),
                 summary["map"]["snapshots_received"].get<std::size_t>(),
                 latency["p50_ms"].get<double>(), latency["p99_ms"].get<double>(),
                 latency["max_ms"].get<double>(), latency["count"].get<std::size_t>());
    for (const std::string& file : files) std::cerr << " " << file;
    std::cerr << " in " << options_.out << "\n";
  }

  using PoseReader = dds::Reader<msg::PoseWithCovarianceStampedPubSubType>;
  using MapReader = dds::Reader<msg::OccupancyMapPubSubType>;
  using KeyframePosesReader = dds::Reader<msg::KeyframePosesPubSubType>;
  using StatusReader = dds::Reader<msg::MatcherStatusPubSubType>;
  using ScanReader = dds::Reader<msg::LaserScanPubSubType>;

  StationOptions options_;
  process::NodeOptions node_;
  std::string vehicle_;
  ground_station::FlightRecord record_;
  dds::Participant participant_;
  std::unique_ptr<PoseReader> pose_;
  std::unique_ptr<MapReader> map_;
  std::unique_ptr<KeyframePosesReader> keyframe_poses_;
  std::unique_ptr<StatusReader> status_;
  std::unique_ptr<ScanReader> scans_;
};

void apply_own_config(const CLI::App& app, const io::YamlReader& section, StationOptions& o) {
  section.expect_keys_only({"out", "latency", "status_period", "quiet"});
  if (process::unset(app, "--out")) o.out = section.get_string_or("out", o.out);
  if (process::unset(app, "--latency")) o.latency = section.get_bool_or("latency", o.latency);
  if (process::unset(app, "--status-period")) {
    o.status_period =
        section.get_double_or("status_period", o.status_period, io::NumberRange::positive());
  }
  if (process::unset(app, "--quiet")) o.quiet = section.get_bool_or("quiet", o.quiet);
}

}  // namespace
}  // namespace uavslam

int main(int argc, char** argv) {
  CLI::App app{
      "ground_station: subscribes pose, map and matcher_status (and scan, for the scan -> pose "
      "latency), prints a status line every --status-period s and on SIGINT/SIGTERM writes "
      "trajectory.tum, map.bt, map_occupied.ply, map_topdown.png and summary.json to --out"};
  uavslam::process::NodeOptions node;
  uavslam::StationOptions options;
  uavslam::process::add_node_options(app, node);
  app.add_option("--out", options.out, "output directory (created if missing)")
      ->capture_default_str();
  app.add_flag("--latency,!--no-latency", options.latency,
               "measure scan -> pose latency: pose arrival here minus the scan's DDS source "
               "timestamp (also subscribes scan). Exact on one host; across hosts the clocks "
               "must be synchronised (PTP/chrony), or the figure is off by their offset. "
               "Default: on");
  app.add_option("--status-period", options.status_period, "seconds between status lines")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_flag("--quiet", options.quiet, "no status lines or final summary (errors still shown)");
  if (const auto code = uavslam::process::parse_command_line(app, argc, argv)) return *code;
  uavslam::process::install_stop_handler();
  return uavslam::process::run_node("ground_station", [&] {
    if (const auto section = uavslam::process::apply_node_config(app, node, "ground_station")) {
      uavslam::apply_own_config(app, *section, options);
    }
    uavslam::GroundStation station(node, options);
    return station.run();
  });
}
