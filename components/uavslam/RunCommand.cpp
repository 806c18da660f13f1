// uavslam run: the SLAM pipeline over a recorded CARMEN log (the Freiburg 2D benchmark logs): the
// robot's odometry heading is the orientation source (these robots had no IMU), its motion the
// ICP's prior where the config asks for one, and the config's heading mode decides whether the
// matcher corrects the heading; written as OUT/estimate.txt for `uavslam eval --relations`,
// OUT/estimate.tum, OUT/map.ply and OUT/summary.json.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "Commands.hpp"
#include "RunSummary.hpp"
#include "common/StopRequest.hpp"
#include "core/Heading.hpp"
#include "core/OdometryPrior.hpp"
#include "core/SlamPipeline.hpp"
#include "eval/Percentile.hpp"
#include "io/CarmenLog.hpp"
#include "io/CarmenTimeline.hpp"
#include "io/FileError.hpp"
#include "io/PlyFile.hpp"
#include "io/TumFile.hpp"

namespace uavslam::cli {
namespace {

struct RunOptions {
  std::string carmen;
  std::string out;
  std::string config;
  std::vector<std::string> overrides;
  bool quiet = false;
  double heading_jitter = 0.0;  // rad
  unsigned jitter_seed = 1;
};

// A robustness probe: each scan's odometry heading moved by a tiny pseudo-random amount (uniform
// in +-amplitude, reproducible from the seed). A matcher whose result changes a lot under 1e-6
// rad is chaotic, and one run's figure says little about it (data README).
class HeadingJitter {
 public:
  HeadingJitter(double amplitude, unsigned seed) : amplitude_(amplitude), random_(seed) {}
  double next() {
    return amplitude_ > 0.0
               ? std::uniform_real_distribution<double>(-amplitude_, amplitude_)(random_)
               : 0.0;
  }

 private:
  double amplitude_;
  std::mt19937 random_;
};

// The pipeline's ImuBuffer needs strictly increasing stamps, and intel.clf's ipc_timestamps run
// backwards: the pipeline runs on the log's timeline, derived from file order.
using MonotonicClock = io::CarmenTimeline;

// A scan with a pose: matched, or (rejected with a motion prior) dead-reckoned by the odometry.
struct AcceptedScan {
  double ipc_timestamp = 0.0;  // the scan's own stamp, which the relations refer to
  Pose pose;                   // stamped with the ipc_timestamp too
  double theta = 0.0;          // the heading: odometry's, plus the matcher's correction if any
};

struct LogRun {
  std::vector<AcceptedScan> accepted;
  std::vector<double> scan_seconds;
  OutcomeCounts outcomes{};
  std::size_t scans_in = 0;
  std::size_t keyframes = 0;
  std::size_t dead_reckoned = 0;  // rejected scans given the odometry's pose
  std::size_t malformed_lines = 0;
  std::vector<std::string> problems;
  Points map;
  double first_stamp = std::numeric_limits<double>::infinity();
  double last_stamp = -std::numeric_limits<double>::infinity();
  double read_seconds = 0.0;
  double wall_seconds = 0.0;  // pipeline only
  bool stopped_early = false;

  double log_seconds() const { return scans_in > 0 ? last_stamp - first_stamp : 0.0; }
  std::size_t accepted_count() const { return cli::accepted_count(outcomes); }
};

// One geometry per distinct beam layout and laser mount (a log normally has one).
class GeometryCache {
 public:
  std::shared_ptr<const ScanGeometry> for_scan(const io::CarmenScan& scan) {
    const Eigen::Isometry3d mount = io::laser_mount(scan);
    if (!geometry_ || scan.ranges.size() != beams_ || scan.start_angle != start_ ||
        scan.angle_increment != increment_ || scan.max_range != max_range_ ||
        !mount.isApprox(geometry_->mount, 0.0)) {
      geometry_ = std::make_shared<const ScanGeometry>(io::to_scan_geometry(scan));
      beams_ = scan.ranges.size();
      start_ = scan.start_angle;
      increment_ = scan.angle_increment;
      max_range_ = scan.max_range;
    }
    return geometry_;
  }

 private:
  std::shared_ptr<const ScanGeometry> geometry_;
  std::size_t beams_ = 0;
  double start_ = 0.0;
  double increment_ = 0.0;
  double max_range_ = 0.0;
};

std::vector<const io::CarmenScan*> scans_in_file_order(const io::CarmenLog& log) {
  std::vector<const io::CarmenScan*> scans;
  for (const io::CarmenMessage& message : log.messages) {
    if (const auto* scan = std::get_if<io::CarmenScan>(&message)) scans.push_back(scan);
  }
  return scans;
}

// The robot's odometry pose is the body: the first scan seeds the map there, its heading is the
// orientation source, and the laser sits on it where the message says (GeometryCache). The
// relations of the Freiburg benchmark refer to this pose.
void process_log(const io::CarmenLog& log, const SlamConfig& config, HeadingJitter jitter,
                 LogRun& run, const std::function<void(std::size_t, std::size_t)>& progress) {
  using Clock = std::chrono::steady_clock;
  const std::vector<const io::CarmenScan*> scans = scans_in_file_order(log);
  if (scans.empty()) return;
  const io::CarmenPose2& start = scans.front()->robot_pose;
  SlamPipeline slam(config, Vec3(start.x, start.y, 0.0));
  MonotonicClock clock;
  GeometryCache geometries;
  // The ICP's motion prior (icp.motion_prior: odometry): the robot's odometry motion since the
  // last scan that got a pose, in the odometry's frame (the pipeline turns it by its heading
  // correction); the same piece the matcher process feeds from the `odom` topic.
  const bool use_odometry = config.icp.motion_prior == "odometry";
  OdometryPrior odometry(config.imu.max_gap);
  const auto run_start = Clock::now();
  for (std::size_t i = 0; i < scans.size(); ++i) {
    if (process::stop_requested()) {
      run.stopped_early = true;
      break;
    }
    const io::CarmenScan& carmen = *scans[i];
    const double theta = carmen.robot_pose.theta + jitter.next();
    Scan scan = io::to_core_scan(carmen, geometries.for_scan(carmen), i);
    scan.stamp = clock.next(carmen.ipc_timestamp);
    const auto started = Clock::now();
    slam.add_imu({scan.stamp, yaw_rotation(theta), Vec3::Zero(), Vec3::Zero()});
    if (use_odometry)
      odometry.add({scan.stamp, Vec3(carmen.robot_pose.x, carmen.robot_pose.y, 0.0)});
    const Vec3 predicted = use_odometry ? odometry.motion_to(scan.stamp) : Vec3::Zero();
    const ScanReport report = slam.process_scan(scan, predicted);
    run.scan_seconds.push_back(std::chrono::duration<double>(Clock::now() - started).count());
    ++run.scans_in;
    run.first_stamp = std::min(run.first_stamp, carmen.ipc_timestamp);
    run.last_stamp = std::max(run.last_stamp, carmen.ipc_timestamp);
    run.keyframes += report.map_updated;
    run.dead_reckoned += report.dead_reckoned;
    if (report.accepted() || report.dead_reckoned) {
      odometry.scan_posed(scan.stamp);
      Pose pose = report.pose;
      pose.stamp = carmen.ipc_timestamp;
      run.accepted.push_back({carmen.ipc_timestamp, pose, heading_of(pose.orientation)});
    }
    if (progress && i % 200 == 0) progress(i, scans.size());
  }
  run.wall_seconds = std::chrono::duration<double>(Clock::now() - run_start).count();
  run.outcomes = slam.outcome_counts();
  run.map = slam.map().points();
  if (progress) progress(run.scans_in, scans.size());
}

void write_estimate(const std::string& path, const std::vector<AcceptedScan>& accepted) {
  std::ofstream out(path);
  out << std::fixed;
  for (const AcceptedScan& a : accepted) {
    out << std::setprecision(6) << a.ipc_timestamp << ' ' << std::setprecision(6)
        << a.pose.position.x() << ' ' << a.pose.position.y() << ' ' << a.theta << '\n';
  }
  if (!out) throw io::file_error(path, "cannot write");
}

nlohmann::json to_json(const LogRun& run, const std::string& log_path,
                       const eval::SampleStats& ms) {
  const nlohmann::json rejected = rejected_by_reason(run.outcomes);
  nlohmann::json j;
  j["log"] = log_path;
  j["stopped_early"] = run.stopped_early;
  j["malformed_lines"] = run.malformed_lines;
  j["problems"] = run.problems;
  j["scans"] = {{"in", run.scans_in},
                {"accepted", run.accepted_count()},
                {"rejected", run.scans_in - run.accepted_count()},
                {"rejected_by_reason", rejected},
                {"dead_reckoned", run.dead_reckoned}};
  j["map"] = {{"points", run.map.size()}, {"keyframes", run.keyframes}};
  j["matcher_ms_per_scan"] = {{"mean", ms.mean}, {"p50", ms.p50}, {"p99", ms.p99}, {"max", ms.max}};
  j["read_seconds"] = run.read_seconds;
  j["wall_seconds"] = run.wall_seconds;
  j["log_seconds"] = run.log_seconds();
  j["real_time_factor"] = run.wall_seconds > 0.0 ? run.log_seconds() / run.wall_seconds : 0.0;
  return j;
}

void print_summary(std::ostream& out, const LogRun& run, const std::string& log_path,
                   const eval::SampleStats& ms) {
  out << "uavslam run: " << log_path << (run.stopped_early ? " (stopped early)" : "") << "\n";
  print_scan_counts(out, run.scans_in, run.outcomes);
  if (run.dead_reckoned > 0) {
    out << "  dead-reckoned     " << run.dead_reckoned
        << " rejected scans given the odometry's pose\n";
  }
  out << "  malformed lines   " << run.malformed_lines << "\n";
  out << "  map               " << run.map.size() << " points from " << run.keyframes
      << " keyframes\n";
  out << std::fixed << std::setprecision(3) << "  matcher time      " << ms.mean
      << " ms/scan mean, p99 " << ms.p99 << " ms, max " << ms.max << " ms\n";
  const double factor = run.wall_seconds > 0.0 ? run.log_seconds() / run.wall_seconds : 0.0;
  out << std::setprecision(2) << "  wall time         " << run.wall_seconds << " s for "
      << run.log_seconds() << " s of log (" << std::setprecision(1) << factor
      << "x real time); reading the log " << std::setprecision(2) << run.read_seconds << " s\n";
}

void write_outputs(const std::filesystem::path& out, const LogRun& run,
                   const nlohmann::json& summary) {
  std::filesystem::create_directories(out);
  write_estimate((out / "estimate.txt").string(), run.accepted);
  std::vector<Pose> poses;
  poses.reserve(run.accepted.size());
  for (const AcceptedScan& a : run.accepted) poses.push_back(a.pose);
  io::write_tum((out / "estimate.tum").string(), poses);
  io::write_ply((out / "map.ply").string(), run.map);
  const std::string json_path = (out / "summary.json").string();
  std::ofstream json(json_path);
  json << summary.dump(2) << "\n";
  if (!json) throw io::file_error(json_path, "cannot write");
}

int run_log(const RunOptions& o) {
  const SlamConfig config = load_config(o.config, o.overrides);
  if (!o.quiet) std::cerr << "reading " << o.carmen << " ...\n";
  const auto read_start = std::chrono::steady_clock::now();
  const io::CarmenLog log = io::read_carmen_log(o.carmen);
  LogRun run;
  run.read_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - read_start).count();
  run.malformed_lines = log.malformed_lines;
  run.problems = log.problems;
  for (const std::string& problem : log.problems) std::cerr << "skipped " << problem << "\n";
  process_log(log, config, HeadingJitter(o.heading_jitter, o.jitter_seed), run,
              [&](std::size_t done, std::size_t total) {
                if (!o.quiet) report_progress("SLAM", done, total);
              });
  std::vector<double> ms;
  ms.reserve(run.scan_seconds.size());
  for (double seconds : run.scan_seconds) ms.push_back(seconds * 1e3);
  const eval::SampleStats stats = eval::summarize(ms);
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
  cmd->add_option("--config", options->config,
                  "SLAM parameters YAML (e.g. config/slam_2d_logs.yaml; default: the built-in "
                  "defaults, as in config/slam.yaml)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", options->overrides,
                  "override one SLAM parameter, e.g. --set icp.iterations=12 (repeatable)");
  cmd->add_flag("--quiet", options->quiet, "no progress on stderr");
  cmd->add_option("--heading-jitter", options->heading_jitter,
                  "robustness probe: add a pseudo-random heading offset, uniform in +-RAD, to each "
                  "scan's odometry heading (e.g. 1e-6; default 0)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--jitter-seed", options->jitter_seed,
                  "seed of --heading-jitter (runs with the same seed are identical; default 1)");
  cmd->callback([options, &exit_code] { exit_code = run_log(*options); });
}

}  // namespace uavslam::cli
