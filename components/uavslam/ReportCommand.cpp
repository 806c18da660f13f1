// uavslam report: the summary of a run of the distributed system (`make demo`): what the sensors
// published, what the matcher did with it, what reached the ground station (poses, map, latency),
// and the trajectory error of the poses the ground station received against the simulator's truth.
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

#include <nlohmann/json.hpp>

#include "Commands.hpp"
#include "RunSummary.hpp"
#include "io/FileError.hpp"
#include "io/TumFile.hpp"

namespace uavslam::cli {
namespace {

namespace fs = std::filesystem;

struct ReportOptions {
  std::string run;
  std::string ground_station = "ground_station";  // relative to run
  std::string groundtruth = "groundtruth.tum";    // relative to run
};

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io::file_error(path, "cannot open");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw io::file_error(path, std::string("not JSON: ") + e.what());
  }
}

void print_outputs(const fs::path& run, const fs::path& gcs, const nlohmann::json& summary) {
  std::cout << "  outputs           " << gcs.string() << "/{";
  const char* separator = "";
  for (const auto& file : summary.value("files", nlohmann::json::array())) {
    std::cout << separator << file.get<std::string>();
    separator = ", ";
  }
  std::cout << "}\n                    " << run.string() << "/logs/*.log";
  for (const char* extra : {"recording_000.mcap", "map_server"}) {
    if (fs::exists(run / extra)) std::cout << ", " << (run / extra).string();
  }
  std::cout << "\n";
}

int run_report(const ReportOptions& o) {
  const fs::path run(o.run), gcs = run / o.ground_station;
  const nlohmann::json summary = read_json((gcs / "summary.json").string());
  const std::vector<Pose> truth = io::read_tum((run / o.groundtruth).string());
  const std::vector<Pose> poses = io::read_tum((gcs / "trajectory.tum").string());
  const nlohmann::json& status = summary.at("matcher_status");
  const nlohmann::json& latency = summary.at("latency_scan_to_pose");
  const nlohmann::json& map = summary.at("map");

  std::cout << std::fixed << "uavslam report: " << run.string() << "\n"
            << "  scans             " << truth.size() << " published, "
            << status.at("scans_received").get<std::uint64_t>() << " received by the matcher, "
            << status.at("scans_accepted").get<std::uint64_t>() << " matched, "
            << status.at("scans_skipped").get<std::uint64_t>() << " skipped (behind newer ones), "
            << status.at("scans_rejected").get<std::uint64_t>() << " rejected\n"
            << "  ground station    " << poses.size() << " poses at " << std::setprecision(1)
            << summary.at("poses").at("rate_hz").get<double>() << " Hz; map snapshot "
            << map.at("last_map_seq") << ": " << map.at("map_points").get<std::uint64_t>()
            << " points, " << map.at("occupied_cells").get<std::uint64_t>() << " occupied cells of "
            << std::setprecision(2) << map.at("resolution_m").get<double>() << " m\n"
            << "  latency           scan -> pose at the ground station: p50 "
            << std::setprecision(2) << latency.at("p50_ms").get<double>() << " ms, p99 "
            << latency.at("p99_ms").get<double>() << " ms, max "
            << latency.at("max_ms").get<double>() << " ms over "
            << latency.at("count").get<std::uint64_t>() << " poses\n";
  const eval::TrajectoryErrors errors = eval::compare_trajectories(poses, truth);
  std::cout << std::setprecision(4) << "  ATE RMSE          " << errors.ate_rmse
            << " m (horizontal " << errors.ate_horizontal_rmse << " m, vertical "
            << errors.ate_vertical_rmse << " m, max " << errors.ate_max << " m) over "
            << errors.pairs << " poses\n";
  print_outputs(run, gcs, summary);
  return 0;
}

}  // namespace

void add_report_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ReportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "summary of a run of the DDS processes (make demo): scans published / matched / skipped, "
      "poses and map at the ground station, scan-to-pose latency, ATE against the ground truth");
  cmd->add_option("run", options->run, "the run's output directory (e.g. out/demo)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--ground-station", options->ground_station,
                  "the ground station's --out, relative to the run directory")
      ->capture_default_str();
  cmd->add_option("--groundtruth", options->groundtruth,
                  "the lidar_driver's --groundtruth TUM file, relative to the run directory")
      ->capture_default_str();
  cmd->callback([options, &exit_code] { exit_code = run_report(*options); });
}

}  // namespace uavslam::cli
