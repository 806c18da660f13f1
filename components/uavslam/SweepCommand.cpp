// uavslam sweep: the seed fixed its iteration count "through testing"; this is that test. One
// simulated flight, the pipeline run for every (iterations, FLANN checks) pair, one table row each.
#include <iomanip>
#include <iostream>
#include <sstream>

#include "Commands.hpp"
#include "RunSummary.hpp"
#include "SimulatedFlight.hpp"
#include "common/StopRequest.hpp"
#include "io/ScenarioFile.hpp"

namespace uavslam::cli {
namespace {

struct SweepOptions {
  std::string scenario;
  std::string config;
  std::vector<std::string> overrides;
  std::vector<int> iterations{1, 2, 3, 5, 10, 15, 20, 30};
  std::vector<std::string> checks{"4", "8", "16", "32", "64", "128", "exact"};
};

std::string format_row(int iterations, const std::string& checks, const RunSummary& s) {
  std::ostringstream row;
  row << std::fixed << "| " << iterations << " | " << checks << " | ";
  if (s.errors) {
    row << std::setprecision(3) << s.errors->ate_horizontal_rmse << " | "
        << s.errors->ate_vertical_rmse << " | ";
  } else {
    row << "n/a | n/a | ";
  }
  row << std::setprecision(1) << 100.0 * double(s.accepted()) / double(s.run->scans_in) << " | "
      << std::setprecision(3) << s.scan_ms.mean << " | " << s.scan_ms.p99 << " |";
  return row.str();
}

int run_sweep(const SweepOptions& o) {
  const sim::Scenario scenario = io::load_scenario(o.scenario);
  const SlamConfig base = load_config(o.config, o.overrides);
  std::cerr << "simulating " << scenario.name << " ...\n";
  const SensorLog log = simulate_sensors(scenario);
  std::cout
      << "Scenario `" << scenario.name << "`, " << log.scans.size() << " scans, "
      << base.scan.subsample_every << "-th point subsampling.\n\n"
      << "| iterations | FLANN checks | ATE horizontal (m) | ATE vertical (m) | accepted (%) | "
         "ms/scan mean | ms/scan p99 |\n|---|---|---|---|---|---|---|\n";
  for (const std::string& checks : o.checks) {
    for (int iterations : o.iterations) {
      if (process::stop_requested()) return 130;
      SlamConfig config = base;
      config.icp.iterations = iterations;
      if (checks == "exact") {
        config.nearest_neighbour.index = IndexKind::Exact;
      } else {
        config.nearest_neighbour.index = IndexKind::Flann;
        config.nearest_neighbour.flann_checks = std::stoi(checks);
      }
      const SlamRun run = run_slam(log, config);
      std::cout << format_row(iterations, checks, summarize_run(scenario.name, run, log.duration))
                << std::endl;
    }
  }
  return 0;
}

}  // namespace

void add_sweep_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Accuracy and time per scan against ICP iterations and FLANN checks on one "
      "simulated flight (a Markdown table)");
  cmd->add_option("--scenario", options->scenario, "scenario YAML")
      ->required()
      ->check(CLI::ExistingFile);
  add_slam_config_options(
      *cmd, options->config, options->overrides,
      "SLAM parameters YAML (default: the built-in defaults: the seed, as in config/seed.yaml)");
  cmd->add_option("--iterations", options->iterations, "iteration counts to try")
      ->delimiter(',')
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--checks", options->checks, "FLANN checks to try; 'exact' for the octree")
      ->delimiter(',')
      ->check(CLI::IsMember({"exact"}) | CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([options, &exit_code] { exit_code = run_sweep(*options); });
}

}  // namespace uavslam::cli
