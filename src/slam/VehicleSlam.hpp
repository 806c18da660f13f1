// One vehicle's SLAM, for every caller: the matcher process (slam_matcher), `uavslam run`,
// `uavslam offline` and `uavslam simulate` all run this object and only move data in and out.
// It owns the core's pipeline (SlamPipeline) and what goes around it:
//   - the motion prior: the motion since the last posed scan that the ICP starts from and that
//     carries the directions the scan cannot see: the odometry's (icp.motion_prior odometry,
//     OdometryPrior) or the IMU's accelerations integrated (icp.motion_prior imu, InertialPrior);
//   - the sensor's mount: where the scanner was when a keyframe was taken, the rays' origin;
//   - the keyframe products: what each keyframe adds to the map, and, for the offline variant,
//     the dense cloud of every posed scan and the occupancy octree of the keyframes;
//   - the tracking state: tracking, degraded or lost, and why (TrackingMonitor);
//   - the pose-graph back end (loop_closure.enabled, backend/KeyframeGraph): every keyframe into
//     the graph; when a loop moves the keyframes, the pipeline's map is rebuilt on them and the
//     motion prior moves with it; so too when the heading drift the pipeline learnt turns the
//     keyframes made before it (SlamPipeline::heading_turns);
//   - the map's first frame: while the pipeline may still turn it onto the orientation source's
//     heading (icp.heading_anchor), the keyframes wait for the back end and the scans for the
//     dense products, and go in turned with it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>

#include "backend/KeyframeGraph.hpp"
#include "core/SlamConfig.hpp"
#include "core/SlamPipeline.hpp"
#include "maps/DenseCloud.hpp"
#include "maps/OccupancyOctree.hpp"
#include "slam/GraphWorker.hpp"
#include "slam/InertialPrior.hpp"
#include "slam/OdometryPrior.hpp"
#include "slam/TrackingMonitor.hpp"

namespace uavslam {

// The offline variant's dense products (seed 5.4.3.3); none in real time.
struct DenseProducts {
  std::optional<double> cloud_voxel;         // m; <= 0 keeps every point
  std::optional<OccupancyConfig> occupancy;  // the OctoMap of the keyframes' full scans
};

// What a keyframe adds to the map, as the map's consumers take it (the map server, the offline
// occupancy map).
struct Keyframe {
  std::uint32_t index = 0;            // 0, 1, ... in the order the keyframes were made
  Pose body;                          // the body's pose at the keyframe, stamped
  Vec3 sensor_origin = Vec3::Zero();  // where the scanner was: the origin of its rays
  Points points;                      // the aligned points it added to the world map
};

// Where a posed scan was relative to the newest keyframe when it was made: the back end moves the
// scan with that keyframe (VehicleSlam::smoothed).
struct ScanAnchor {
  std::size_t keyframe = 0;
  backend::Constraint offset;  // the scan's pose seen from the keyframe's
};

// Where the back end runs: in the scan's call (a run over a log is then the same every time), or
// on a thread of its own (the matcher process: the scan's path never waits for it).
using BackendThreading = GraphWorker::Threading;

struct VehicleScan {
  ScanReport report;  // its added_points are moved into keyframe
  std::optional<Keyframe> keyframe;
  double pipeline_seconds = 0.0;     // the matching alone (motion prior and pipeline)
  TrackingStatus tracking;           // tracking, degraded or lost, and why
  std::optional<ScanAnchor> anchor;  // with the back end, for a posed scan
  bool map_corrected = false;        // the back end moved the keyframes and rebuilt the map
  double heading_drift = 0.0;        // rad/s: the source's, as learnt (SlamPipeline::heading_drift)

  // The scan got a pose: matched, or (rejected with a motion prior) dead-reckoned.
  bool posed() const { return report.accepted() || report.dead_reckoned; }
};

class VehicleSlam {
 public:
  explicit VehicleSlam(const SlamConfig& config, const DenseProducts& products = {},
                       BackendThreading threading = BackendThreading::Inline);

  // Where the body is at the first scan (the take-off point): the map's frame is anchored there.
  // Before the first scan; the origin when never called.
  void start_at(const Vec3& position) { pipeline_.start_at(position); }

  // The orientation source's samples; with icp.motion_prior imu, their specific force too.
  void add_imu(const ImuSample& sample);
  // Wheel odometry for the motion prior; ignored unless icp.motion_prior is odometry. A
  // non-finite or out-of-order sample is dropped and counted (odometry_prior()->rejected()).
  void add_odometry(const OdometrySample& sample);
  // The autopilot's velocity for the IMU prior; ignored unless icp.motion_prior is imu and
  // motion.fuse_velocity is set. A bad sample is dropped and counted
  // (inertial_prior()->rejected_velocities()).
  void add_velocity(const VelocitySample& sample);

  // skipped_before: scans the caller dropped unprocessed just before this one (it fell behind);
  // they make the tracking state degraded (overload).
  VehicleScan process_scan(const Scan& scan, std::size_t skipped_before = 0);

  const SlamPipeline& pipeline() const { return pipeline_; }
  const SlamConfig& config() const { return pipeline_.config(); }
  // Null unless icp.motion_prior is odometry.
  const OdometryPrior* odometry_prior() const { return odometry_ ? &*odometry_ : nullptr; }
  // Null unless icp.motion_prior is imu.
  const InertialPrior* inertial_prior() const { return inertial_ ? &*inertial_ : nullptr; }
  std::size_t keyframes() const { return keyframes_; }
  // With the back end: every keyframe's pose in the map's current frame (the graph's where it
  // has them); what consumers of the keyframes move their points to after a correction.
  const std::vector<backend::NodePose>& keyframe_poses() const { return keyframe_poses_; }
  // Every keyframe's scan stamp, in keyframe order (the pipeline's).
  const std::vector<double>& keyframe_stamps() const { return pipeline_.keyframe_stamps(); }

  // The back end's loop counts (none unless loop_closure.enabled).
  std::optional<backend::LoopCounts> loops() const;
  // The end of a run: the graph optimised once more and the map rebuilt on it. False without a
  // back end.
  bool finish();
  // A posed scan's pose where the graph now puts its keyframe (unchanged without a back end).
  Pose smoothed(const Pose& pose, const ScanAnchor& anchor) const;

  // The dense products (null when not asked for), and the seconds spent building them.
  const DenseCloud* cloud() const { return cloud_.get(); }
  const OccupancyOctree* occupancy() const { return occupancy_.get(); }
  std::unique_ptr<DenseCloud> take_cloud() { return std::move(cloud_); }
  std::unique_ptr<OccupancyOctree> take_occupancy() { return std::move(occupancy_); }
  double cloud_seconds() const { return cloud_seconds_; }
  // The graph's: searching loops, optimising, and (inline) rebuilding the map after it moved.
  double backend_seconds() const;
  double occupancy_seconds() const { return occupancy_seconds_; }

 private:
  MotionPrediction predicted_motion(double stamp);
  void scan_posed(const ScanReport& report);
  Keyframe keyframe_of(const Scan& scan, ScanReport& report);
  void add_dense(const Scan& scan, const Pose& pose, const SweepMotion& sweep,
                 const Vec3* sensor_origin);
  void add_to_graph(const ScanReport& report);
  bool apply_graph_update();
  void turn_frame(const FrameTurn& turn);

  // What waits for the map's heading to settle (SlamPipeline::frame_settled): the keyframes for
  // the back end and the scans for the dense products, in the map's first frame.
  struct UnsettledScan {
    Scan scan;
    Pose pose;
    SweepMotion sweep;
    std::optional<Vec3> sensor_origin;  // a keyframe's
  };
  std::vector<GraphKeyframe> unsettled_keyframes_;
  std::vector<UnsettledScan> unsettled_scans_;

  SlamPipeline pipeline_;
  std::optional<OdometryPrior> odometry_;
  std::optional<InertialPrior> inertial_;
  TrackingMonitor tracking_;
  std::unique_ptr<DenseCloud> cloud_;
  std::unique_ptr<OccupancyOctree> occupancy_;
  std::unique_ptr<GraphWorker> graph_;
  std::size_t frame_ = 0;                          // the back end's updates applied
  std::size_t headings_turned_ = 0;                // heading turns handed to the back end, and
  std::size_t headings_turned_applied_ = 0;        // those its updates applied
  std::vector<backend::NodePose> keyframe_poses_;  // in the map's current frame
  std::vector<backend::NodePose> final_poses_;     // the graph's after finish()
  double inline_update_seconds_ = 0.0;             // rebuilding the map after an inline update
  std::size_t keyframes_ = 0;
  double cloud_seconds_ = 0.0;
  double occupancy_seconds_ = 0.0;
};

}  // namespace uavslam
