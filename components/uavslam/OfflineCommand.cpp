// uavslam offline: the seed's offline variant (thesis 5.4.3.3) over a recorded or simulated
// flight. It runs the same matching steps with every point of every scan and exact nearest
// neighbours (the octree), keeps every point of every posed scan as a dense cloud (voxel-filtered
// so memory follows the space mapped, not the log's length), ray-casts the keyframes into an
// OctoMap, and reports how it compares with the real-time pass over the same data.
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "Commands.hpp"
#include "LogInput.hpp"
#include "LogPass.hpp"
#include "ProgressBar.hpp"
#include "SimulatedFlight.hpp"
#include "eval/Percentile.hpp"
#include "eval/TrajectoryMetrics.hpp"
#include "io/FileError.hpp"
#include "io/OctreeFile.hpp"
#include "io/PcdFile.hpp"
#include "io/PlyFile.hpp"
#include "io/RelationsFile.hpp"
#include "io/ScenarioFile.hpp"
#include "io/TumFile.hpp"
#include "sensor/LidarGeometry.hpp"
#include "sim/World.hpp"

namespace uavslam::cli {
namespace {

struct OfflineOptions {
  std::string carmen;
  std::string scenario;
  std::string log;      // an MCAP recording
  std::string sensor;   // the scenario whose sensor (and world) the recording's scans are of
  std::string vehicle;  // the recording's vehicle whose channels are mapped ("" = the only one)
  std::string out;
  std::string config;
  std::vector<std::string> overrides;
  double voxel = 0.01;
  std::optional<double> map_spacing;  // unset: 0.02 m for a 3D flight, the config's for CARMEN
  double octomap_resolution = 0.1;
  bool skip_realtime = false;
  bool quiet = false;
};

// A 3D flight's keyframes, every point of each, map a place as often as the vehicle sees it: a
// point within this distance of a map point is not added. On the demo flight the map shrank from
// 269,000 to 152,000 points (the exact search's cost) and the dense pass matched better, ATE 0.033
// -> 0.027 m (docs/recordings.md "Offline dense mapping"). Not for CARMEN logs: on FR079 it cost
// the point-to-line matcher its loop (0.031 -> 0.12 m over all relations).
constexpr double kFlightMapSpacing = 0.02;

// The seed's offline variant of a configuration: every point of a scan is matched and every point
// of a keyframe enters the map (but for `map_spacing`), and the nearest neighbours are exact
// (octree), not FLANN's.
SlamConfig offline_variant(SlamConfig config, std::optional<double> map_spacing) {
  config.scan.subsample_every = 1;
  config.map.subsample_every = 1;
  config.nearest_neighbour.index = IndexKind::Exact;
  if (map_spacing) config.map.min_point_spacing = *map_spacing;
  return config;
}

struct Input {
  LogInputFactory open;
  std::unique_ptr<LogInput> opened;  // opened already (to check it), for the first pass
  std::string name;
  std::optional<sim::World> world;  // the true surfaces, for a simulated flight
  bool planar_estimate = false;     // CARMEN: also estimate.txt for `uavslam eval --relations`
};

// An MCAP recording: with --sensor, its scans are of that scenario's LiDAR (mount, mirror) and its
// world gives the cloud's distance to the true surfaces; without, each scan's beam layout is a
// planar scanner at the body origin.
Input open_log_input(const OfflineOptions& o) {
  std::shared_ptr<const ScanGeometry> geometry;
  std::optional<sim::World> world;
  if (!o.sensor.empty()) {
    const sim::Scenario scenario = io::load_scenario(o.sensor);
    geometry = make_scan_geometry(scenario.lidar);
    world.emplace(scenario.world);
  }
  // Opened now, so a file it cannot map is refused before any output is made.
  std::unique_ptr<LogInput> opened = open_mcap_input(o.log, geometry, o.vehicle);
  return {[path = o.log, geometry, vehicle = o.vehicle] {
            return open_mcap_input(path, geometry, vehicle);
          },
          std::move(opened), o.log, std::move(world), false};
}

Input open_input(const OfflineOptions& o) {
  if (!o.log.empty()) return open_log_input(o);
  if (!o.carmen.empty()) {
    return {[path = o.carmen] { return open_carmen_input(path); }, nullptr, o.carmen, std::nullopt,
            true};
  }
  const sim::Scenario scenario = io::load_scenario(o.scenario);
  auto log = std::make_shared<const SensorLog>(simulate_sensors(scenario));
  return {[log] { return open_simulated_input(log); }, nullptr, o.scenario,
          sim::World(scenario.world), false};
}

PassResult run_one_pass(Input& input, const PassOptions& options, const char* label,
                        const OfflineOptions& o) {
  std::unique_ptr<LogInput> log = input.opened ? std::move(input.opened) : input.open();
  std::optional<ProgressBar> bar;
  if (!o.quiet) bar.emplace(label, log->expected_scans(), "scans", std::cerr, isatty(2) != 0);
  return run_pass(*log, options, bar ? &*bar : nullptr, o.quiet ? nullptr : &std::cerr);
}

// Mean and max distance of points to the simulated world's surfaces (the cloud's quality).
nlohmann::json surface_distances(const sim::World& world, const std::vector<Vec3>& points) {
  std::vector<double> d;
  d.reserve(points.size());
  for (const Vec3& p : points) d.push_back(world.distance_to_nearest_surface(p));
  const eval::SampleStats s = eval::summarize(d);
  return {{"points", points.size()},
          {"mean_m", s.mean},
          {"p50_m", s.p50},
          {"p99_m", s.p99},
          {"max_m", s.max}};
}

std::vector<Vec3> positions(const std::vector<DensePoint>& cloud) {
  std::vector<Vec3> p;
  p.reserve(cloud.size());
  for (const DensePoint& point : cloud) p.push_back(point.position);
  return p;
}

std::optional<eval::TrajectoryErrors> compare(const std::vector<Pose>& estimate,
                                              const std::vector<Pose>& reference) {
  try {
    return eval::compare_trajectories(estimate, reference);
  } catch (const std::invalid_argument&) {
    return std::nullopt;  // too few poses in common: the report says so by its absence
  }
}

nlohmann::json pass_json(const PassResult& pass) {
  std::vector<double> ms = pass.scan_ms;
  const eval::SampleStats s = eval::summarize(ms);
  nlohmann::json j = {
      {"scans", pass.scans_in},
      {"posed", pass.posed.size()},
      {"accepted", accepted_count(pass.outcomes)},
      {"rejected_by_reason", rejected_by_reason(pass.outcomes)},
      {"dead_reckoned", pass.dead_reckoned},
      {"keyframes", pass.keyframes},
      {"map_points", pass.map.size()},
      {"wall_seconds", pass.wall_seconds},
      {"data_seconds", pass.data_seconds},
      {"real_time_factor", pass.real_time_factor()},
      {"scans_per_second", pass.wall_seconds > 0 ? pass.scans_in / pass.wall_seconds : 0.0},
      {"ms_per_scan", {{"mean", s.mean}, {"p99", s.p99}, {"max", s.max}}}};
  if (auto ate = compare(pass.estimate(), pass.ground_truth())) j["errors"] = to_json(*ate);
  return j;
}

void write_products(const std::filesystem::path& out, const PassResult& dense,
                    const std::vector<DensePoint>& cloud, bool planar_estimate) {
  io::write_ply((out / "cloud.ply").string(), cloud);
  io::write_pcd((out / "cloud.pcd").string(), cloud);
  io::write_bt((out / "map.bt").string(), dense.occupancy->pruned_tree());
  io::write_tum((out / "estimate.tum").string(), dense.estimate());
  if (planar_estimate)
    io::write_planar_estimate((out / "estimate.txt").string(), dense.planar_estimate());
}

nlohmann::json make_report(const Input& input, const PassResult& dense,
                           const std::vector<DensePoint>& cloud, const PassResult* realtime) {
  nlohmann::json report;
  report["input"] = input.name;
  report["stopped_early"] = dense.stopped_early || (realtime && realtime->stopped_early);
  if (!dense.input_damage.empty()) report["input_damage"] = dense.input_damage;
  report["malformed_records"] = dense.malformed;
  report["offline"] = pass_json(dense);
  report["offline"]["cloud"] = {{"points", cloud.size()},
                                {"points_before_voxel_filter", dense.cloud->points_added()},
                                {"voxel_m", dense.cloud->voxel()},
                                {"octomap_occupied_leaves", dense.occupancy->occupied_leaves()},
                                {"cloud_seconds", dense.cloud_seconds},
                                {"octomap_seconds", dense.occupancy_seconds}};
  if (input.world) {
    report["offline"]["cloud"]["distance_to_true_surfaces"] =
        surface_distances(*input.world, positions(cloud));
  }
  if (!realtime) return report;
  report["realtime"] = pass_json(*realtime);
  if (input.world) {
    report["realtime"]["map_distance_to_true_surfaces"] =
        surface_distances(*input.world, realtime->map);
  }
  if (auto difference = compare(dense.estimate(), realtime->estimate())) {
    report["trajectory_difference"] = to_json(*difference);
  }
  return report;
}

void print_pass(std::ostream& out, const char* name, const nlohmann::json& j) {
  out << std::fixed << std::setprecision(2) << "  " << name << j["scans"].get<std::size_t>()
      << " scans (" << j["posed"].get<std::size_t>() << " posed) in "
      << j["wall_seconds"].get<double>() << " s: " << std::setprecision(0)
      << j["scans_per_second"].get<double>() << " scans/s, " << std::setprecision(3)
      << j["ms_per_scan"]["mean"].get<double>() << " ms/scan, " << std::setprecision(1)
      << j["real_time_factor"].get<double>() << "x real time";
  if (j.contains("errors")) {
    out << std::setprecision(4) << ", ATE " << j["errors"]["ate_rmse_m"].get<double>() << " m";
  }
  out << "\n";
}

void print_report(std::ostream& out, const nlohmann::json& r) {
  out << "uavslam offline: " << r["input"].get<std::string>()
      << (r["stopped_early"].get<bool>() ? " (stopped early)" : "")
      << (r.contains("input_damage") ? " (cut short: the complete part mapped)" : "") << "\n";
  if (r.contains("input_damage")) {
    out << "  input cut short   " << r["input_damage"].get<std::string>() << "\n";
  }
  print_pass(out, "offline (dense)  ", r["offline"]);
  if (r.contains("realtime")) print_pass(out, "real-time        ", r["realtime"]);
  const nlohmann::json& cloud = r["offline"]["cloud"];
  out << "  dense cloud       " << cloud["points"].get<std::size_t>() << " points ("
      << cloud["points_before_voxel_filter"].get<std::uint64_t>() << " before the "
      << std::setprecision(3) << cloud["voxel_m"].get<double>() << " m voxel filter; "
      << std::setprecision(2) << cloud["cloud_seconds"].get<double>() << " s, OctoMap "
      << cloud["octomap_seconds"].get<double>() << " s)";
  if (cloud.contains("distance_to_true_surfaces")) {
    out << std::setprecision(4) << ", mean distance to the true surfaces "
        << cloud["distance_to_true_surfaces"]["mean_m"].get<double>() << " m";
  }
  out << "\n";
  if (r.contains("trajectory_difference")) {
    const nlohmann::json& d = r["trajectory_difference"];
    out << std::setprecision(4) << "  offline vs real-time trajectory: mean "
        << d["ate_mean_m"].get<double>() << " m, max " << d["ate_max_m"].get<double>() << " m\n";
  }
}

int run_offline(const OfflineOptions& o) {
  // A CARMEN log with no --config: the configuration made for real 2D logs, as `uavslam run`.
  const std::string config_path =
      o.config.empty() && !o.carmen.empty() ? shipped_config(kLogsConfig) : o.config;
  const SlamConfig config = load_config(config_path, o.overrides);
  if (!o.quiet) {
    std::cerr << "uavslam offline: reading "
              << (!o.log.empty()     ? o.log
                  : o.carmen.empty() ? o.scenario
                                     : o.carmen)
              << "\n";
  }
  Input input = open_input(o);
  std::filesystem::create_directories(o.out);
  const std::optional<double> map_spacing =
      o.map_spacing ? o.map_spacing
                    : (o.carmen.empty() ? std::optional<double>(kFlightMapSpacing) : std::nullopt);
  PassOptions dense_options{
      offline_variant(config, map_spacing),
      {o.voxel, OccupancyConfig{o.octomap_resolution, -1.0, 0.7, 0.4, /*batch=*/true}}};
  PassResult dense = run_one_pass(input, dense_options, "offline  ", o);
  std::optional<PassResult> realtime;
  if (!o.skip_realtime && !dense.stopped_early) {
    PassOptions realtime_options;
    realtime_options.config = config;
    realtime = run_one_pass(input, realtime_options, "real-time", o);
  }
  const std::vector<DensePoint> cloud = dense.cloud->points();
  const std::filesystem::path out(o.out);
  write_products(out, dense, cloud, input.planar_estimate);
  const nlohmann::json report = make_report(input, dense, cloud, realtime ? &*realtime : nullptr);
  const std::string report_path = (out / "report.json").string();
  std::ofstream json(report_path);
  json << report.dump(2) << "\n";
  if (!json) throw io::file_error(report_path, "cannot write");
  print_report(std::cout, report);
  std::cout << "  outputs           " << o.out << "/{cloud.ply, cloud.pcd, map.bt, estimate.tum"
            << (input.planar_estimate ? ", estimate.txt" : "") << ", report.json}\n";
  if (report["stopped_early"].get<bool>()) return 130;
  return report.contains("input_damage") ? 1 : 0;
}

}  // namespace

void add_offline_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<OfflineOptions>();
  CLI::App* cmd = app.add_subcommand(
      "offline",
      "The offline dense mapper (the seed's offline variant): every point of every scan, exact "
      "nearest neighbours (octree), the same matching steps; writes OUT/cloud.ply and "
      "OUT/cloud.pcd (binary, x y z intensity time), OUT/map.bt (OctoMap), OUT/estimate.tum "
      "(and OUT/estimate.txt for a CARMEN log) and OUT/report.json, which compares it with the "
      "real-time pass over the same data");
  auto* source = cmd->add_option_group("input", "what to map (one of)");
  source->add_option("--carmen", options->carmen, "CARMEN log (.clf)")->check(CLI::ExistingFile);
  source
      ->add_option("--scenario", options->scenario,
                   "scenario YAML, flown in the simulator first (its world gives the cloud's "
                   "distance to the true surfaces)")
      ->check(CLI::ExistingFile);
  CLI::Option* log =
      source
          ->add_option("--log", options->log,
                       "MCAP recording (uavslam simulate --log, the recorder): its scan, imu and, "
                       "when there, ground_truth channels; a file cut short maps its complete "
                       "part and exits 1")
          ->check(CLI::ExistingFile);
  source->require_option(1);
  cmd->add_option("--sensor", options->sensor,
                  "with --log: the scenario YAML whose LiDAR recorded the scans (mount, floor "
                  "mirror; its world gives the cloud's distance to the true surfaces); without "
                  "it each scan is a planar scanner at the body origin")
      ->check(CLI::ExistingFile)
      ->needs(log);
  cmd->add_option("--vehicle", options->vehicle,
                  "with --log: map this vehicle's channels (VEHICLE/scan, VEHICLE/imu, as its "
                  "processes' --vehicle named them); default: the recording's only vehicle")
      ->needs(log);
  cmd->add_option("--out", options->out, "output folder (created)")->required();
  add_slam_config_options(*cmd, options->config, options->overrides,
                          "SLAM parameters YAML of the real-time pass; the offline pass uses it "
                          "with every point and the exact index (default: the built-in "
                          "defaults, the seed's; for --carmen config/slam_2d_logs.yaml)");
  cmd->add_option("--voxel", options->voxel,
                  "edge of the dense cloud's voxel filter in m: one point (the centroid) per "
                  "voxel; 0 keeps every point (default 0.01)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--map-spacing", options->map_spacing,
                  "the dense pass's map: a keyframe point this close (m) to a map point is not "
                  "added (default 0.02 for a flight, --log or --scenario; for --carmen the "
                  "config's map.min_point_spacing)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--octomap-resolution", options->octomap_resolution,
                  "leaf size of OUT/map.bt in m (default 0.1, as the map server)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--skip-realtime", options->skip_realtime,
                "do not run the real-time pass (no comparison in the report)");
  cmd->add_flag("--quiet", options->quiet, "no progress on stderr");
  cmd->callback([options, &exit_code] { exit_code = run_offline(*options); });
}

}  // namespace uavslam::cli
