// One pass of a vehicle's SLAM (slam/VehicleSlam) over a flight's sensor data (LogInput), as fast
// as it goes: the real-time pass of the seed, or its offline variant, which also keeps every point
// of every posed scan (DenseCloud) and ray-casts each keyframe's points into an OctoMap.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "LogInput.hpp"
#include "ProgressBar.hpp"
#include "RunSummary.hpp"
#include "core/SlamConfig.hpp"
#include "eval/Relation.hpp"
#include "maps/DenseCloud.hpp"
#include "maps/OccupancyOctree.hpp"
#include "slam/VehicleSlam.hpp"

namespace uavslam::cli {

struct PassOptions {
  SlamConfig config;
  DenseProducts products;  // none in the real-time pass
};

// A scan that got a pose: matched, or (rejected with a motion prior) dead-reckoned.
struct PosedScan {
  double output_stamp = 0.0;
  Pose pose;  // stamped with output_stamp
  std::optional<Pose> truth;
  bool dead_reckoned = false;
};

struct PassResult {
  std::vector<PosedScan> posed;
  std::vector<double> scan_ms;     // pipeline (matcher) time of every scan
  double cloud_seconds = 0.0;      // adding the posed scans to the dense cloud
  double occupancy_seconds = 0.0;  // ray-casting the keyframes into the OctoMap
  OutcomeCounts outcomes{};
  std::size_t scans_in = 0;
  std::size_t keyframes = 0;
  std::size_t dead_reckoned = 0;
  std::size_t yaw_held = 0;  // scans whose yaw the scan could not see: the odometry's kept
  // Points set aside where earlier beams saw empty space (free_space.enabled), and in how many
  // scans.
  std::size_t moving_points = 0;
  std::size_t scans_with_moving_points = 0;
  TrackingCounts tracking;
  std::size_t malformed = 0;
  std::vector<std::string> problems;  // descriptions of the malformed records the input kept
  Points map;                         // the matcher's world map
  std::unique_ptr<DenseCloud> cloud;
  std::unique_ptr<OccupancyOctree> occupancy;
  double wall_seconds = 0.0;  // the whole pass: pipeline and dense products
  double data_seconds = 0.0;
  bool stopped_early = false;
  std::string input_damage;                        // LogInput::damage(): the input was cut short
  std::optional<io::NoReturnCode> no_return_code;  // LogInput::no_return_code()
  std::optional<backend::LoopCounts> loops;        // with the back end (loop_closure.enabled)
  double backend_seconds = 0.0;                    // its share of wall_seconds

  double real_time_factor() const { return wall_seconds > 0 ? data_seconds / wall_seconds : 0; }
  double pipeline_seconds() const;  // the matcher's share of wall_seconds (sum of scan_ms)
  std::vector<Pose> estimate() const;
  std::vector<Pose> ground_truth() const;  // where known, at the posed scans
  // "timestamp x y theta" per posed scan (the output stamps), for `uavslam eval --relations`.
  std::vector<eval::PlanarStamped> planar_estimate() const;
};

// Runs until the input ends or a stop is requested (Ctrl-C: stopped_early). Problems the input
// reports (malformed records) go to problems as they are met.
PassResult run_pass(LogInput& input, const PassOptions& options, ProgressBar* progress,
                    std::ostream* problems);

}  // namespace uavslam::cli
