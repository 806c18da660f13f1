// What the ground station has received of one vehicle's flight: the poses, the scan -> pose
// latencies, the last matcher status and the last map snapshot. Fed from the DDS receive threads,
// read by the main loop (status line) and written out when the station stops.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <octomap/OcTree.h>
#include <nlohmann/json.hpp>

#include "ScanPoseLatency.hpp"
#include "backend/TrajectoryCorrection.hpp"
#include "core/Types.hpp"

namespace uavslam::ground_station {

// The matcher's running totals from its latest status.
struct MatcherCounters {
  std::uint64_t scans_received = 0;
  std::uint64_t scans_skipped = 0;
  std::uint64_t scans_rejected = 0;
  std::uint64_t scans_accepted = 0;
  std::string last_outcome;
  std::string tracking;  // "tracking", "degraded" or "lost"
  std::string tracking_reason;
  std::uint64_t loops_searched = 0;  // the matcher's back end (0 without one)
  std::uint64_t loops_accepted = 0;
  std::uint64_t corrections = 0;
  double heading_drift_deg_per_min = 0.0;  // the IMU's, as the matcher learnt it (0: none)
};

// What a map snapshot says about itself.
struct MapSnapshotInfo {
  std::uint64_t map_seq = 0;
  std::uint64_t map_points = 0;
  std::uint64_t occupied_cells = 0;
  double resolution = 0.0;
};

class FlightRecord {
 public:
  using Clock = std::chrono::steady_clock;

  explicit FlightRecord(std::size_t latency_window = 1000);

  // received_at: system clock, seconds since the epoch (the clock DDS source timestamps use).
  void add_pose(const Pose& pose, std::uint64_t scan_seq, double received_at);
  void add_malformed_pose();
  void add_scan(std::uint64_t scan_seq, double published_at);
  void set_matcher_status(const MatcherCounters& counters);
  void set_map(std::shared_ptr<const octomap::OcTree> tree, const MapSnapshotInfo& info);
  void add_malformed_map();
  // The matcher's back end moved the keyframes (`keyframe_poses`): each keyframe's scan stamp
  // and corrected pose (yaw only), every keyframe made so far, from the stamped scan on.
  void add_correction(backend::StampedKeyframes correction);

  // "gcs: 39.8 Hz pose, latency p50 0.9 ms p99 2.1 ms, degraded (degenerate), accepted 1234
  // rejected 3 skipped 0, map 54000 pts / 3120 occupied cells (snapshot 12)": rate and latency
  // since the previous call, the matcher's latest tracking state.
  std::string status_line();

  // Totals for summary.json; `files` lists what write_outputs wrote.
  nlohmann::json summary() const;

  // Writes into `dir` (created if missing): trajectory.tum, pose_arrivals.csv (when each pose
  // arrived here, for link studies) and summary.json always; once a correction came,
  // keyframes.tum (the keyframes where the last one put them) and trajectory_corrected.tum (each
  // pose moved with its keyframe, backend/TrajectoryCorrection); map.bt and
  // map_occupied.ply once a map arrived; map_topdown.png once a map or a pose did. Returns the
  // names written. Throws io::FileError naming the file that could not be written.
  std::vector<std::string> write_outputs(const std::string& dir);

 private:
  // Per pose, in arrival order: when it arrived (system clock) and its latency if known then.
  struct Arrival {
    std::uint64_t scan_seq;
    double received_at;
    std::optional<double> latency_ms;
  };
  static void write_arrivals(const std::string& file, const std::vector<Pose>& poses,
                             const std::vector<Arrival>& arrivals);

  mutable std::mutex mutex_;
  ScanPoseLatency latency_join_;
  std::vector<Pose> poses_;
  std::vector<double> latencies_ms_;
  std::vector<Arrival> arrivals_;
  std::optional<double> first_pose_at_;
  double last_pose_at_ = 0.0;
  std::uint64_t malformed_poses_ = 0;
  std::uint64_t statuses_ = 0;
  MatcherCounters counters_;
  std::shared_ptr<const octomap::OcTree> map_;
  MapSnapshotInfo map_info_;
  std::uint64_t maps_ = 0;
  std::uint64_t malformed_maps_ = 0;
  std::vector<backend::StampedKeyframes> corrections_;
  // Where the previous status line left off.
  Clock::time_point line_time_ = Clock::now();
  std::size_t line_poses_ = 0;
  std::size_t line_latencies_ = 0;
  // Set by write_outputs for the summary.
  std::vector<std::string> files_;
  std::optional<nlohmann::json> picture_;
};

}  // namespace uavslam::ground_station
