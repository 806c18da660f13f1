// uavslam simulate: fly a scenario in the simulator, run the SLAM pipeline on it, write the
// trajectories, the map and a summary.
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <stdexcept>

#include <unistd.h>

#include "Commands.hpp"
#include "ProgressBar.hpp"
#include "RunSummary.hpp"
#include "SimulatedFlight.hpp"
#include "common/StopRequest.hpp"
#include "io/FileError.hpp"
#include "io/PlyFile.hpp"
#include "io/ScenarioFile.hpp"
#include "io/SimulatedCarmenLog.hpp"
#include "io/TumFile.hpp"
#include "io/YamlReader.hpp"

namespace uavslam::cli {
namespace {

struct SimulateOptions {
  std::string scenario;
  std::string out;
  std::string config;
  std::vector<std::string> overrides;
  std::string log;                    // MCAP recording of the flight, when given
  std::string carmen;                 // the flight as a ground robot's CARMEN log, when given
  std::optional<std::uint64_t> seed;  // the sensors' noise seed instead of the scenario's
  bool quiet = false;
};

// Per-scan diagnostics, one CSV row per scan, for plotting and for finding where a run went wrong.
void write_trace(const std::string& path, const std::vector<ScanTrace>& trace) {
  std::ofstream csv(path);
  csv << "stamp,outcome,points,error_before,error_after,iterations,keyframe,x,y,z,true_x,true_y,"
         "true_z,ms,degenerate,weakest_fraction,sigma_x,sigma_y,sigma_z,prior_distance,tracking,"
         "tracking_reason,floor_returns,nees\n";
  for (const ScanTrace& t : trace) {
    csv << std::fixed << std::setprecision(4) << t.stamp << ',' << to_string(t.outcome) << ','
        << t.points_used << ',' << std::setprecision(6) << t.error_before << ',' << t.error_after
        << ',' << t.iterations << ',' << t.map_updated << ',' << std::setprecision(4)
        << t.position.x() << ',' << t.position.y() << ',' << t.position.z() << ',' << t.truth.x()
        << ',' << t.truth.y() << ',' << t.truth.z() << ',' << t.milliseconds << ',' << t.degenerate
        << ',' << t.weakest_fraction << ',' << t.sigma.x() << ',' << t.sigma.y() << ','
        << t.sigma.z() << ',' << t.prior_distance << ',' << to_string(t.tracking.state) << ','
        << to_string(t.tracking.reason) << ',' << t.floor_returns << ',';
    if (t.nees) csv << t.nees->value;
    csv << '\n';
  }
  if (!csv) throw io::file_error(path, "cannot write");
}

void write_outputs(const std::filesystem::path& out, const SlamRun& run,
                   const std::vector<Pose>& ground_truth, const nlohmann::json& summary) {
  std::filesystem::create_directories(out);
  io::write_tum((out / "estimate.tum").string(), run.estimate);
  io::write_tum((out / "groundtruth.tum").string(), ground_truth);
  io::write_ply((out / "map.ply").string(), run.map);
  write_trace((out / "scans.csv").string(), run.trace);
  const std::string json_path = (out / "summary.json").string();
  std::ofstream json(json_path);
  json << summary.dump(2) << "\n";
  if (!json) throw io::file_error(json_path, "cannot write");
}

// FILE.clf and, beside it, FILE.relations.
std::string relations_path(const std::string& carmen) {
  return std::filesystem::path(carmen).replace_extension(".relations").string();
}

void write_carmen(const std::string& path, const sim::Scenario& scenario, const SensorLog& log,
                  bool quiet) {
  const std::string relations = relations_path(path);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (!folder.empty()) std::filesystem::create_directories(folder);
  try {
    const io::SimulatedCarmenFiles files =
        io::write_simulated_carmen_log(path, relations, scenario, log.scans, log.ground_truth);
    if (quiet) return;
    std::cerr << "wrote " << path << " (" << files.scans << " scans, " << std::fixed
              << std::setprecision(1) << files.path_length << " m driven) and " << relations << " ("
              << files.relations << " relations)\n";
  } catch (const std::invalid_argument& e) {
    throw io::ConfigError("--carmen: the scenario " + scenario.name + ": " + e.what());
  }
}

int run_simulate(const SimulateOptions& o) {
  sim::Scenario scenario = io::load_scenario(o.scenario);
  if (o.seed) scenario.seed = *o.seed;
  const SlamConfig config = load_config(o.config, o.overrides);
  if (!o.quiet) std::cerr << "simulating " << scenario.name << " ...\n";
  const SensorLog log = simulate_sensors(scenario);
  if (!o.log.empty()) write_flight_log(o.log, scenario, log);
  if (!o.carmen.empty()) write_carmen(o.carmen, scenario, log, o.quiet);
  std::optional<ProgressBar> bar;  // on a terminal only: a log file gets the summary alone
  if (!o.quiet && isatty(2)) bar.emplace("SLAM", log.scans.size(), "scans", std::cerr, true);
  const SlamRun run = run_slam(log, config, [&](std::size_t done, std::size_t total) {
    if (!bar) return;
    if (done >= total) {
      bar->finish(done);
    } else {
      bar->update(done);
    }
  });
  const RunSummary summary = summarize_run(scenario.name, run, log.duration);
  write_outputs(o.out, run, log.ground_truth, to_json(summary, config));
  print_summary(std::cout, summary);
  std::cout << "  outputs           " << o.out
            << "/{estimate.tum, groundtruth.tum, map.ply, scans.csv, summary.json}"
            << (o.log.empty() ? "" : ", " + o.log)
            << (o.carmen.empty() ? "" : ", " + o.carmen + ", " + relations_path(o.carmen)) << "\n";
  return run.stopped_early ? 130 : 0;
}

}  // namespace

void add_simulate_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Simulate a scenario's flight and sensors, run the SLAM pipeline on it and write "
      "OUT/estimate.tum, OUT/groundtruth.tum (TUM: t x y z qx qy qz qw), OUT/map.ply, "
      "OUT/scans.csv (per-scan diagnostics) and OUT/summary.json");
  cmd->add_option("--scenario", options->scenario,
                  "scenario YAML (e.g. config/scenarios/demo.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options->out, "output folder (created)")->required();
  add_slam_config_options(
      *cmd, options->config, options->overrides,
      "SLAM parameters YAML (default: the built-in defaults: the seed, as in config/seed.yaml)");
  cmd->add_option("--log", options->log,
                  "also write the flight's sensor data as an MCAP recording: channels scan, imu "
                  "and ground_truth, as the sensor processes publish them (replay it with "
                  "lidar_driver/imu_bridge --source mcap:FILE, map it with uavslam offline --log)");
  cmd->add_option("--carmen", options->carmen,
                  "also write the flight as a ground robot's CARMEN log FILE.clf (the planar "
                  "scanner as ROBOTLASER1 messages, the scenario's `odometry` as the wheels' "
                  "poses) and the relations of its true path as FILE.relations: score `uavslam "
                  "run --carmen FILE.clf` with `uavslam eval --relations FILE.relations`");
  cmd->add_option("--seed", options->seed,
                  "seed of the sensors' noise instead of the scenario's: the same flight with "
                  "other noise, for Monte Carlo runs (test/bench/monte_carlo.sh)");
  cmd->add_flag("--quiet", options->quiet, "no progress on stderr");
  cmd->callback([options, &exit_code] { exit_code = run_simulate(*options); });
}

}  // namespace uavslam::cli
