#include "RunSummary.hpp"

#include <cmath>
#include <iomanip>
#include <ostream>

#include "core/Angles.hpp"

namespace uavslam::cli {

double RunSummary::real_time_factor() const {
  return run->wall_seconds > 0.0 ? flight_seconds / run->wall_seconds : 0.0;
}

std::size_t RunSummary::accepted() const {
  return accepted_count(run->outcomes);
}

RunSummary summarize_run(const std::string& scenario, const SlamRun& run, double flight_seconds) {
  RunSummary s;
  s.scenario = scenario;
  s.run = &run;
  s.flight_seconds = flight_seconds;
  std::vector<double> ms;
  ms.reserve(run.scan_seconds.size());
  for (double seconds : run.scan_seconds) ms.push_back(seconds * 1e3);
  s.scan_ms = eval::summarize(ms);
  try {
    s.errors = eval::compare_trajectories(run.estimate, run.ground_truth);
    if (!run.smoothed.empty()) {
      s.smoothed_errors = eval::compare_trajectories(run.smoothed, run.ground_truth);
    }
  } catch (const std::invalid_argument& e) {
    s.errors_unavailable = e.what();
  }
  return s;
}

void print_errors(std::ostream& out, const eval::TrajectoryErrors& e) {
  out << std::fixed << std::setprecision(4);
  out << "  ATE RMSE          " << e.ate_rmse << " m (horizontal " << e.ate_horizontal_rmse
      << " m, vertical " << e.ate_vertical_rmse << " m, max " << e.ate_max << " m) over " << e.pairs
      << " poses\n";
  out << "  RPE per " << std::setprecision(1) << e.rpe_delta << " s      " << std::setprecision(4)
      << e.rpe_translation_rmse << " m, " << e.rpe_rotation_rmse_deg << " deg (RMSE over "
      << e.rpe_pairs << " pairs)\n";
  out << "  final position    " << e.final_position_error << " m off\n";
}

namespace {
bool is_accepted(ScanOutcome outcome) {
  return outcome == ScanOutcome::Accepted || outcome == ScanOutcome::MapInitialised;
}
}  // namespace

std::size_t accepted_count(const OutcomeCounts& outcomes) {
  std::size_t accepted = 0;
  for (std::size_t k = 0; k < kScanOutcomeCount; ++k) {
    if (is_accepted(ScanOutcome(k))) accepted += outcomes[k];
  }
  return accepted;
}

void print_scan_counts(std::ostream& out, std::size_t scans_in, const OutcomeCounts& outcomes) {
  const std::size_t accepted = accepted_count(outcomes);
  out << "  scans             " << scans_in << " in, " << accepted << " accepted, "
      << scans_in - accepted << " rejected";
  std::string separator = " (";
  for (std::size_t k = 0; k < kScanOutcomeCount; ++k) {
    if (is_accepted(ScanOutcome(k)) || outcomes[k] == 0) continue;
    out << separator << to_string(ScanOutcome(k)) << " " << outcomes[k];
    separator = ", ";
  }
  out << (separator == ", " ? ")" : "") << "\n";
}

nlohmann::json rejected_by_reason(const OutcomeCounts& outcomes) {
  nlohmann::json rejected = nlohmann::json::object();
  for (std::size_t k = 0; k < kScanOutcomeCount; ++k) {
    if (!is_accepted(ScanOutcome(k))) rejected[to_string(ScanOutcome(k))] = outcomes[k];
  }
  return rejected;
}

void print_moving_points(std::ostream& out, std::size_t points, std::size_t scans) {
  if (points == 0) return;
  out << "  moving points     " << points << " in " << scans
      << " scans, where earlier beams saw empty space, left out (people, doors)\n";
}

void print_tracking(std::ostream& out, const TrackingCounts& tracking) {
  out << "  tracking          ";
  for (std::size_t k = 0; k < tracking.states.size(); ++k) {
    const std::string state = to_string(Tracking(k));
    out << (k > 0 ? ", " : "") << tracking.states[k] << ' ' << state;
    std::string separator = " (";
    for (const auto& [key, count] : tracking.reasons) {
      if (key.rfind(state + ": ", 0) != 0) continue;
      out << separator << key.substr(state.size() + 2) << ' ' << count;
      separator = ", ";
    }
    if (separator == ", ") out << ')';
  }
  out << '\n';
}

nlohmann::json to_json(const TrackingCounts& tracking) {
  return {{"tracking", tracking.states[0]},
          {"degraded", tracking.states[1]},
          {"lost", tracking.states[2]},
          {"by_reason", tracking.reasons}};
}

void print_loops(std::ostream& out, const backend::LoopCounts& loops, double seconds) {
  out << "  loops             " << backend::describe(loops) << ", " << std::fixed
      << std::setprecision(2) << seconds << " s\n";
}

nlohmann::json to_json(const backend::LoopCounts& loops, double seconds) {
  return {{"seconds", seconds},
          {"searched", loops.searches},
          {"accepted", loops.accepted},
          {"rejected_score", loops.rejected_score},
          {"rejected_look_alike", loops.rejected_ambiguous},
          {"rejected_back_to_back", loops.rejected_back_to_back},
          {"rejected_by_graph", loops.rejected_by_graph},
          {"optimisations", loops.optimisations}};
}

namespace {
// Points set aside over the flight, and the scans they were in: a tilted scanner's level beams
// on the floor (ScanTrace::floor_returns, scan.floor_margin), what moved there
// (ScanTrace::moving_points, free_space).
struct SetAside {
  std::size_t points = 0;
  std::size_t scans = 0;
};

// Scans whose trace has `flag` set: ScanTrace::height_from_floor (the floor's level measured the
// height, floor.level_gate), ScanTrace::blind_fixed (a structure across the blind direction fixed
// it, degeneracy.search_window).
std::size_t scans_with(const SlamRun& run, bool ScanTrace::*flag) {
  std::size_t count = 0;
  for (const ScanTrace& t : run.trace) count += t.*flag;
  return count;
}

SetAside set_aside(const SlamRun& run, std::size_t ScanTrace::*count) {
  SetAside total;
  for (const ScanTrace& t : run.trace) {
    total.points += t.*count;
    total.scans += t.*count > 0;
  }
  return total;
}
}  // namespace

void print_summary(std::ostream& out, const RunSummary& s) {
  const SlamRun& run = *s.run;
  out << "uavslam simulate: " << s.scenario << (run.stopped_early ? " (stopped early)" : "")
      << "\n";
  print_scan_counts(out, run.scans_in, run.outcomes);
  if (const SetAside strikes = set_aside(run, &ScanTrace::floor_returns); strikes.points > 0) {
    out << "  floor strikes     " << strikes.points << " points set aside in " << strikes.scans
        << " scans (level beams of the tilted scanner on the floor)\n";
  }
  const SetAside moving = set_aside(run, &ScanTrace::moving_points);
  print_moving_points(out, moving.points, moving.scans);
  if (const std::size_t floor = scans_with(run, &ScanTrace::height_from_floor); floor > 0) {
    out << "  floor level       the height measured from the take-off floor's level in " << floor
        << " of " << s.accepted() << " matched scans\n";
  }
  out << "  map               " << run.map.size() << " points from " << run.keyframes
      << " keyframes\n";
  print_tracking(out, run.tracking);
  if (const std::size_t fixed = scans_with(run, &ScanTrace::blind_fixed); fixed > 0) {
    out << "  blind fixed       " << fixed
        << " scans' blind direction fixed by a structure across it (a jamb, an end wall)\n";
  }
  if (run.loops) print_loops(out, *run.loops, run.backend_seconds);
  if (s.errors) {
    print_errors(out, *s.errors);
    if (s.smoothed_errors) {
      out << std::fixed << std::setprecision(4) << "  ATE after loops   "
          << s.smoothed_errors->ate_rmse << " m (max " << s.smoothed_errors->ate_max
          << " m): the poses where the back end's final graph puts them\n";
    }
  } else {
    out << "  trajectory errors unavailable: " << s.errors_unavailable << "\n";
  }
  if (run.nees.empty()) {
    out << "  consistency       no covariance reported (degeneracy.threshold 0)\n";
  } else {
    const eval::NeesSummary nees = eval::summarize(run.nees);
    out << std::setprecision(2) << "  consistency       NEES mean " << nees.mean << " over "
        << nees.count << " poses (a consistent covariance gives " << nees.mean_dimension << ")\n";
  }
  if (run.heading_drift != 0.0) {
    out << std::setprecision(2) << "  heading drift     " << degrees_per_minute(run.heading_drift)
        << " deg/min: the IMU's, learnt from the heading checks and followed\n";
  }
  if (run.heading_anchor) {
    out << std::setprecision(2) << "  heading anchor    the map turned "
        << rad_to_deg(run.heading_anchor->yaw) << " deg onto the IMU's heading after "
        << run.heading_anchor->after << " s of scans\n";
  }
  if (!run.prior_distances.empty()) {
    const eval::SampleStats d = eval::summarize(run.prior_distances);
    out << std::setprecision(2) << "  match vs prior    p50 " << d.p50 << ", p99 " << d.p99
        << ", max " << d.max << " sigmas\n";
  }
  out << std::fixed << std::setprecision(3);
  out << "  matcher time      " << s.scan_ms.mean << " ms/scan mean, p99 " << s.scan_ms.p99
      << " ms, max " << s.scan_ms.max << " ms\n";
  out << std::setprecision(2) << "  wall time         " << run.wall_seconds << " s for "
      << s.flight_seconds << " s of flight (" << std::setprecision(1) << s.real_time_factor()
      << "x real time)\n";
}

nlohmann::json to_json(const eval::TrajectoryErrors& e) {
  return {{"pairs", e.pairs},
          {"ate_rmse_m", e.ate_rmse},
          {"ate_mean_m", e.ate_mean},
          {"ate_max_m", e.ate_max},
          {"ate_horizontal_rmse_m", e.ate_horizontal_rmse},
          {"ate_vertical_rmse_m", e.ate_vertical_rmse},
          {"rpe_delta_s", e.rpe_delta},
          {"rpe_pairs", e.rpe_pairs},
          {"rpe_translation_rmse_m", std::isfinite(e.rpe_translation_rmse)
                                         ? nlohmann::json(e.rpe_translation_rmse)
                                         : nlohmann::json()},
          {"rpe_rotation_rmse_deg", std::isfinite(e.rpe_rotation_rmse_deg)
                                        ? nlohmann::json(e.rpe_rotation_rmse_deg)
                                        : nlohmann::json()},
          {"final_position_error_m", e.final_position_error}};
}

nlohmann::json to_json(const RunSummary& s, const SlamConfig& config) {
  const SlamRun& run = *s.run;
  const nlohmann::json rejected = rejected_by_reason(run.outcomes);
  nlohmann::json j;
  j["scenario"] = s.scenario;
  j["stopped_early"] = run.stopped_early;
  const SetAside strikes = set_aside(run, &ScanTrace::floor_returns);
  const SetAside moving = set_aside(run, &ScanTrace::moving_points);
  j["scans"] = {{"in", run.scans_in},
                {"accepted", s.accepted()},
                {"rejected", run.scans_in - s.accepted()},
                {"rejected_by_reason", rejected},
                {"floor_strikes", {{"points", strikes.points}, {"scans", strikes.scans}}},
                {"moving_points", {{"points", moving.points}, {"scans", moving.scans}}},
                {"height_from_floor", scans_with(run, &ScanTrace::height_from_floor)},
                {"blind_fixed", scans_with(run, &ScanTrace::blind_fixed)}};
  j["map"] = {{"points", run.map.size()}, {"keyframes", run.keyframes}};
  j["tracking"] = to_json(run.tracking);
  if (!run.nees.empty()) {
    const eval::NeesSummary nees = eval::summarize(run.nees);
    j["consistency"] = {
        {"nees_mean", nees.mean}, {"poses", nees.count}, {"state_dimension", nees.mean_dimension}};
  }
  j["heading_drift_deg_per_min"] = degrees_per_minute(run.heading_drift);
  if (run.heading_anchor) {
    j["heading_anchor"] = {{"turn_deg", rad_to_deg(run.heading_anchor->yaw)},
                           {"after_s", run.heading_anchor->after}};
  }
  if (!run.prior_distances.empty()) {
    const eval::SampleStats d = eval::summarize(run.prior_distances);
    j["match_vs_prior_sigmas"] = {{"p50", d.p50}, {"p99", d.p99}, {"max", d.max}};
  }
  j["trajectory_errors"] = s.errors ? to_json(*s.errors) : nlohmann::json(s.errors_unavailable);
  if (s.smoothed_errors) j["trajectory_errors_after_loops"] = to_json(*s.smoothed_errors);
  if (run.loops) j["loops"] = to_json(*run.loops, run.backend_seconds);
  j["matcher_ms_per_scan"] = {{"mean", s.scan_ms.mean},
                              {"p50", s.scan_ms.p50},
                              {"p99", s.scan_ms.p99},
                              {"max", s.scan_ms.max}};
  j["wall_seconds"] = run.wall_seconds;
  j["flight_seconds"] = s.flight_seconds;
  j["real_time_factor"] = s.real_time_factor();
  j["config"] = {{"subsample_every", config.scan.subsample_every},
                 {"iterations", config.icp.iterations},
                 {"max_translation", config.icp.max_translation},
                 {"max_error_after", config.icp.max_error_after},
                 {"max_error_ratio", config.icp.max_error_ratio},
                 {"max_correspondence_distance", config.icp.max_correspondence_distance},
                 {"index", std::string(mode_name(config.nearest_neighbour.index))},
                 {"flann_trees", config.nearest_neighbour.flann_trees},
                 {"flann_checks", config.nearest_neighbour.flann_checks},
                 {"keyframe_height", config.map.keyframe_height},
                 {"keyframe_lateral", config.map.keyframe_lateral}};
  return j;
}

}  // namespace uavslam::cli
