// What a SLAM run amounts to: scans in / accepted / rejected by reason, map size, trajectory
// errors against the ground truth and timing; printed for people and written as summary.json.
#pragma once

#include <array>
#include <iosfwd>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "SimulatedFlight.hpp"
#include "backend/KeyframeGraph.hpp"
#include "eval/Percentile.hpp"
#include "eval/TrajectoryMetrics.hpp"

namespace uavslam::cli {

struct RunSummary {
  std::string scenario;
  SlamRun const* run = nullptr;
  double flight_seconds = 0.0;
  std::optional<eval::TrajectoryErrors> errors;  // none when too few scans were accepted
  // With the back end: of the same poses where its final graph puts them.
  std::optional<eval::TrajectoryErrors> smoothed_errors;
  std::string errors_unavailable;  // why, when errors is empty
  eval::SampleStats scan_ms;

  double real_time_factor() const;
  std::size_t accepted() const;
};

RunSummary summarize_run(const std::string& scenario, const SlamRun& run, double flight_seconds);

// How many scans ended in each outcome (SlamPipeline::outcome_counts()).
using OutcomeCounts = std::array<std::size_t, kScanOutcomeCount>;

// "  scans             N in, A accepted, R rejected (reason n, ...)" and its JSON: the rejected
// scans by reason.
void print_scan_counts(std::ostream& out, std::size_t scans_in, const OutcomeCounts& outcomes);
nlohmann::json rejected_by_reason(const OutcomeCounts& outcomes);
std::size_t accepted_count(const OutcomeCounts& outcomes);

// "  moving points     120 in 30 scans, where earlier beams saw empty space, left out (people,
// doors)": what free_space set aside in a run or flight (no line when nothing was).
void print_moving_points(std::ostream& out, std::size_t points, std::size_t scans);

// "  tracking          7100 tracking, 80 degraded (degenerate 80), 0 lost" and its JSON.
void print_tracking(std::ostream& out, const TrackingCounts& tracking);
nlohmann::json to_json(const TrackingCounts& tracking);
// "  loops             12 accepted of 240 searched (rejected: 200 score, 20 look-alike, 1 back
// to back, 8 by the graph), 14 optimisations, 1.20 s" and its JSON: the back end's loop search and
// its time.
void print_loops(std::ostream& out, const backend::LoopCounts& loops, double seconds);
nlohmann::json to_json(const backend::LoopCounts& loops, double seconds);
void print_summary(std::ostream& out, const RunSummary& summary);
nlohmann::json to_json(const RunSummary& summary, const SlamConfig& config);
nlohmann::json to_json(const eval::TrajectoryErrors& errors);
void print_errors(std::ostream& out, const eval::TrajectoryErrors& errors);

}  // namespace uavslam::cli
