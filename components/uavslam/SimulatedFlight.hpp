// A simulated flight recorded in memory, and the SLAM pipeline run over it in time order, as the
// matcher process would receive it. Sensor simulation happens before the run, so the run's timing
// is the pipeline's alone.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "backend/KeyframeGraph.hpp"
#include "core/SlamPipeline.hpp"
#include "eval/Consistency.hpp"
#include "sim/Scenario.hpp"
#include "slam/TrackingMonitor.hpp"

namespace uavslam::cli {

struct SensorLog {
  std::vector<ImuSample> imu;
  std::vector<VelocitySample> velocity;  // empty unless the scenario has a velocity source
  std::vector<Scan> scans;
  std::vector<Pose> ground_truth;  // the true body pose at each scan's stamp
  double duration = 0.0;           // s of flight
};

SensorLog simulate_sensors(const sim::Scenario& scenario);

// Writes the flight as an MCAP recording (dds/McapChannels.hpp's convention) with the channels
// `scan` (LaserScan), `imu` (Imu), `ground_truth` (PoseWithCovarianceStamped, the true body
// pose at each scan) and, when the flight has a velocity source, `velocity`
// (TwistWithCovarianceStamped), the messages as lidar_driver and imu_bridge publish them
// (dds/SimulatedSensorMessages.hpp), in time order: at equal stamps the IMU samples first, then
// the truth, then the scan, as the pipeline takes them. log_time = publish_time = the stamp.
// io::FileError when the file cannot be written.
void write_flight_log(const std::string& path, const sim::Scenario& scenario, const SensorLog& log);

// One scan's diagnostics, as the matcher_status topic will carry them.
struct ScanTrace {
  double stamp = 0.0;
  ScanOutcome outcome = ScanOutcome::Malformed;
  std::size_t points_used = 0;
  double error_before = 0.0;
  double error_after = 0.0;
  int iterations = 0;
  bool map_updated = false;
  Vec3 position = Vec3::Zero();  // the estimate after this scan
  Vec3 truth = Vec3::Zero();
  double milliseconds = 0.0;
  int degenerate = 0;             // directions the scan could not see (degeneracy analysis)
  double weakest_fraction = 0.0;  // the information fraction of the weakest horizontal direction
  Vec3 sigma = Vec3::Zero();      // m; the reported position's standard deviation per axis
  double prior_distance = 0.0;    // sigmas between the match and the motion prior's prediction
  TrackingStatus tracking;
  std::size_t floor_returns = 0;   // level beams' points set aside as floor strikes
  bool height_from_floor = false;  // the height measured from the floor's level (floor.level_gate)
  std::optional<eval::Nees> nees;  // of the reported position against the truth
  bool blind_fixed = false;        // a structure fixed the blind direction (search_window)
  std::size_t moving_points = 0;   // points set aside as moved there (free_space)
};

struct SlamRun {
  std::vector<ScanTrace> trace;  // every scan
  std::vector<Pose> estimate;    // one pose per accepted scan, as the vehicle had it
  // With the back end (loop_closure.enabled): the same poses where the final graph puts them.
  std::vector<Pose> smoothed;
  std::optional<backend::LoopCounts> loops;
  double backend_seconds = 0.0;      // the back end's share of wall_seconds
  std::vector<Pose> ground_truth;    // the truth at the same stamps
  std::vector<double> scan_seconds;  // pipeline time of every scan
  std::array<std::size_t, kScanOutcomeCount> outcomes{};
  std::size_t scans_in = 0;
  std::size_t keyframes = 0;
  TrackingCounts tracking;
  std::vector<eval::Nees> nees;         // of every accepted scan whose pose has a covariance
  std::vector<double> prior_distances;  // sigmas, of every accepted match measured against a prior
  // rad/s: the IMU's heading drift, as the heading checks learnt it (0: none followed).
  double heading_drift = 0.0;
  // The map turned onto the IMU's heading (icp.heading_anchor): by how much (rad) and how long
  // after the first scan (s); none without an anchor.
  struct AnchorTurn {
    double yaw = 0.0;
    double after = 0.0;
  };
  std::optional<AnchorTurn> heading_anchor;
  Points map;
  double wall_seconds = 0.0;  // whole run, pipeline only
  bool stopped_early = false;
};

// progress(done, total) is called now and then for long runs.
SlamRun run_slam(const SensorLog& log, const SlamConfig& config,
                 const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace uavslam::cli
