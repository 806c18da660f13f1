// What a SLAM run amounts to: scans in / accepted / rejected by reason, map size, trajectory
// errors against the ground truth and timing; printed for people and written as summary.json.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "SimulatedFlight.hpp"
#include "eval/Percentile.hpp"
#include "eval/TrajectoryMetrics.hpp"

namespace uavslam::cli {

struct RunSummary {
  std::string scenario;
  SlamRun const* run = nullptr;
  double flight_seconds = 0.0;
  std::optional<eval::TrajectoryErrors> errors;  // none when too few scans were accepted
  std::string errors_unavailable;                // why, when errors is empty
  eval::SampleStats scan_ms;

  double real_time_factor() const;
  std::size_t accepted() const;
};

RunSummary summarize_run(const std::string& scenario, const SlamRun& run, double flight_seconds);

void print_summary(std::ostream& out, const RunSummary& summary);
nlohmann::json to_json(const RunSummary& summary, const SlamConfig& config);
nlohmann::json to_json(const eval::TrajectoryErrors& errors);
void print_errors(std::ostream& out, const eval::TrajectoryErrors& errors);

}  // namespace uavslam::cli
