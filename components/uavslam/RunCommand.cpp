// uavslam run: the SLAM pipeline over a recorded CARMEN log (the Freiburg 2D benchmark logs): the
// robot's odometry heading is the orientation source (these robots had no IMU), its motion the
// ICP's prior where the config asks for one, and the config's heading mode decides whether the
// matcher corrects the heading; written as OUT/estimate.txt for `uavslam eval --relations`,
// OUT/estimate.tum, OUT/map.ply and OUT/summary.json.
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "Commands.hpp"
#include "LogInput.hpp"
#include "LogPass.hpp"
#include "RunSummary.hpp"
#include "eval/Percentile.hpp"
#include "io/FileError.hpp"
#include "io/PlyFile.hpp"
#include "io/RelationsFile.hpp"
#include "io/TumFile.hpp"

namespace uavslam::cli {
namespace {

struct RunOptions {
  std::string carmen;
  std::string out;
  std::string config;
  std::vector<std::string> overrides;
  bool quiet = false;
  HeadingJitter jitter;
};

nlohmann::json to_json(const PassResult& run, const std::string& log_path,
                       const eval::SampleStats& ms) {
  const std::size_t accepted = accepted_count(run.outcomes);
  nlohmann::json j;
  j["log"] = log_path;
  j["stopped_early"] = run.stopped_early;
  j["malformed_lines"] = run.malformed;
  j["no_return_range"] =
      run.no_return_code ? nlohmann::json(run.no_return_code->range) : nlohmann::json(nullptr);
  j["problems"] = run.problems;
  j["scans"] = {
      {"in", run.scans_in},
      {"accepted", accepted},
      {"rejected", run.scans_in - accepted},
      {"rejected_by_reason", rejected_by_reason(run.outcomes)},
      {"dead_reckoned", run.dead_reckoned},
      {"yaw_held", run.yaw_held},
      {"moving_points", {{"points", run.moving_points}, {"scans", run.scans_with_moving_points}}}};
  j["tracking"] = cli::to_json(run.tracking);
  j["map"] = {{"points", run.map.size()}, {"keyframes", run.keyframes}};
  if (run.loops) j["loops"] = cli::to_json(*run.loops, run.backend_seconds);
  j["matcher_ms_per_scan"] = {{"mean", ms.mean}, {"p50", ms.p50}, {"p99", ms.p99}, {"max", ms.max}};
  j["wall_seconds"] = run.pipeline_seconds();
  j["total_seconds"] = run.wall_seconds;
  j["log_seconds"] = run.data_seconds;
  j["real_time_factor"] =
      run.pipeline_seconds() > 0.0 ? run.data_seconds / run.pipeline_seconds() : 0.0;
  return j;
}

void print_summary(std::ostream& out, const PassResult& run, const std::string& log_path,
                   const eval::SampleStats& ms) {
  out << "uavslam run: " << log_path << (run.stopped_early ? " (stopped early)" : "") << "\n";
  print_scan_counts(out, run.scans_in, run.outcomes);
  if (run.dead_reckoned > 0) {
    out << "  dead-reckoned     " << run.dead_reckoned
        << " rejected scans given the odometry's pose\n";
  }
  if (run.yaw_held > 0) {
    out << "  yaw held          " << run.yaw_held
        << " scans blind to their turn (a round room) kept the odometry's\n";
  }
  print_moving_points(out, run.moving_points, run.scans_with_moving_points);
  print_tracking(out, run.tracking);
  out << "  malformed lines   " << run.malformed << "\n";
  if (run.no_return_code) {
    out << std::fixed << std::setprecision(2) << "  no return         written as "
        << run.no_return_code->range << " m (" << run.no_return_code->readings
        << " readings, learned from the log)\n";
  }
  out << "  map               " << run.map.size() << " points from " << run.keyframes
      << " keyframes\n";
  if (run.loops) print_loops(out, *run.loops, run.backend_seconds);
  out << std::fixed << std::setprecision(3) << "  matcher time      " << ms.mean
      << " ms/scan mean, p99 " << ms.p99 << " ms, max " << ms.max << " ms\n";
  const double pipeline = run.pipeline_seconds();
  const double factor = pipeline > 0.0 ? run.data_seconds / pipeline : 0.0;
  out << std::setprecision(2) << "  wall time         " << pipeline << " s for " << run.data_seconds
      << " s of log (" << std::setprecision(1) << factor
      << "x real time); the whole pass (reading the log, the back end) " << std::setprecision(2)
      << run.wall_seconds << " s\n";
}

void write_outputs(const std::filesystem::path& out, const PassResult& run,
                   const nlohmann::json& summary) {
  std::filesystem::create_directories(out);
  io::write_planar_estimate((out / "estimate.txt").string(), run.planar_estimate());
  io::write_tum((out / "estimate.tum").string(), run.estimate());
  io::write_ply((out / "map.ply").string(), run.map);
  const std::string json_path = (out / "summary.json").string();
  std::ofstream json(json_path);
  json << summary.dump(2) << "\n";
  if (!json) throw io::file_error(json_path, "cannot write");
}

int run_log(const RunOptions& o) {
  PassOptions options;
  // No --config: the configuration made for real 2D logs, not the seed's (one flag away).
  const std::string config_path = o.config.empty() ? shipped_config(kLogsConfig) : o.config;
  if (!o.quiet && o.config.empty()) {
    std::cerr << "uavslam run: SLAM config " << config_path
              << " (the default for 2D logs; --config config/seed.yaml for the seed's mode)\n";
  }
  options.config = load_config(config_path, o.overrides);
  std::unique_ptr<LogInput> input = open_carmen_input(o.carmen, o.jitter);
  std::optional<ProgressBar> bar;
  if (!o.quiet) bar.emplace("SLAM", input->expected_scans(), "scans", std::cerr, isatty(2) != 0);
  const PassResult run = run_pass(*input, options, bar ? &*bar : nullptr, &std::cerr);
  const eval::SampleStats stats = eval::summarize(std::vector<double>(run.scan_ms));
  write_outputs(o.out, run, to_json(run, o.carmen, stats));
  print_summary(std::cout, run, o.carmen, stats);
  std::cout << "  outputs           " << o.out
            << "/{estimate.txt, estimate.tum, map.ply, summary.json}\n";
  return run.stopped_early ? 130 : 0;
}

}  // namespace

void add_run_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Run the SLAM pipeline over a CARMEN log (e.g. the Freiburg benchmark's intel.clf) in file "
      "order, the odometry heading as the orientation source (corrected by the matcher if the "
      "config's icp.heading says so), and write OUT/estimate.txt (ipc_timestamp x y theta per "
      "scan with a pose, for `uavslam eval --relations`), OUT/estimate.tum, OUT/map.ply and "
      "OUT/summary.json");
  cmd->add_option("--carmen", options->carmen, "CARMEN log (.clf)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options->out, "output folder (created)")->required();
  add_slam_config_options(*cmd, options->config, options->overrides,
                          "SLAM parameters YAML (default: config/slam_2d_logs.yaml, made for real "
                          "2D logs; config/seed.yaml: the seed's mode)");
  cmd->add_flag("--quiet", options->quiet, "no progress on stderr");
  cmd->add_option("--heading-jitter", options->jitter.amplitude,
                  "robustness probe: add a pseudo-random heading offset, uniform in +-RAD, to each "
                  "scan's odometry heading (e.g. 1e-6; default 0)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--jitter-seed", options->jitter.seed,
                  "seed of --heading-jitter (runs with the same seed are identical; default 1)");
  cmd->callback([options, &exit_code] { exit_code = run_log(*options); });
}

}  // namespace uavslam::cli
