#include "slam/VehicleSlam.hpp"

#include <chrono>

#include "core/Angles.hpp"
#include "core/Heading.hpp"
#include "core/ScanProjection.hpp"

namespace uavslam {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

VehicleSlam::VehicleSlam(const SlamConfig& config, const DenseProducts& products,
                         BackendThreading threading)
    : pipeline_(config), tracking_(config.recovery.gap) {
  // The odometry is as much "at the scan's time" as the orientation: the same tolerance.
  if (config.icp.motion_prior == MotionPrior::Odometry) {
    odometry_.emplace(config.imu.max_gap, config.motion);
  }
  if (config.icp.motion_prior == MotionPrior::Imu)
    inertial_.emplace(config.motion, config.imu.max_gap);
  if (products.cloud_voxel) cloud_ = std::make_unique<DenseCloud>(*products.cloud_voxel);
  if (products.occupancy) occupancy_ = std::make_unique<OccupancyOctree>(*products.occupancy);
  if (config.loop_closure.enabled) {
    graph_ = std::make_unique<GraphWorker>(config.loop_closure, threading);
  }
}

void VehicleSlam::add_imu(const ImuSample& sample) {
  pipeline_.add_imu(sample);
  if (inertial_) inertial_->add(sample);
}

void VehicleSlam::add_odometry(const OdometrySample& sample) {
  if (odometry_) odometry_->add(sample);
}

void VehicleSlam::add_velocity(const VelocitySample& sample) {
  if (inertial_ && config().motion.fuse_velocity) inertial_->add_velocity(sample);
}

MotionPrediction VehicleSlam::predicted_motion(double stamp) {
  if (odometry_) return odometry_->motion_to(stamp);
  if (inertial_) return inertial_->motion_to(stamp, pipeline_.heading_correction());
  return {};
}

void VehicleSlam::scan_posed(const ScanReport& report) {
  if (odometry_) odometry_->scan_posed(report.pose.stamp, report.covariance);
  if (inertial_) inertial_->scan_posed(report, pipeline_.heading_correction());
}

// The ICP starts from the motion prior's motion since the last posed scan (none without a prior:
// the seed); a scan that got a pose is the next motion's start.
VehicleScan VehicleSlam::process_scan(const Scan& scan, std::size_t skipped_before) {
  VehicleScan result;
  // The back end's thread may have moved the map since the last scan: the scan waits for the
  // rebuild, so it counts in the scan's time.
  const auto started = Clock::now();
  if (graph_) result.map_corrected = apply_graph_update();
  result.report = pipeline_.process_scan(scan, predicted_motion(scan.stamp));
  if (result.report.frame_turn) {
    turn_frame(*result.report.frame_turn);
    result.map_corrected = true;
  }
  if (result.posed()) scan_posed(result.report);
  result.pipeline_seconds = seconds_since(started);
  result.tracking = tracking_.judge(scan, result.report, skipped_before);
  if (graph_ && result.report.map_updated) add_to_graph(result.report);
  if (graph_ && result.posed()) {
    // Both in the map's frame as the scan was matched in it; the keyframe scan itself: no offset.
    backend::Constraint offset;
    if (!result.report.map_updated) {
      offset = backend::relative(keyframe_poses_.back(), backend::node_of(result.report.pose));
    }
    result.anchor = ScanAnchor{keyframes_ - (result.report.map_updated ? 0 : 1), offset};
  }
  if (graph_) {
    // Inline, the update the keyframe just made: the back end's time.
    const auto applying = Clock::now();
    result.map_corrected = apply_graph_update() || result.map_corrected;
    inline_update_seconds_ += seconds_since(applying);
  }
  if (result.report.map_updated) result.keyframe = keyframe_of(scan, result.report);
  if (result.posed() && (cloud_ || occupancy_)) {
    const Vec3* origin = result.keyframe ? &result.keyframe->sensor_origin : nullptr;
    if (pipeline_.frame_settled()) {
      add_dense(scan, result.report.pose, result.report.sweep, origin);
    } else {
      unsettled_scans_.push_back({scan, result.report.pose, result.report.sweep,
                                  origin ? std::optional<Vec3>(*origin) : std::nullopt});
    }
  }
  result.heading_drift = pipeline_.heading_drift();
  return result;
}

// The scanner's place at the keyframe: the body pose moved by the sensor's mount.
Keyframe VehicleSlam::keyframe_of(const Scan& scan, ScanReport& report) {
  Keyframe keyframe;
  keyframe.index = static_cast<std::uint32_t>(keyframes_++);
  keyframe.body = report.pose;
  keyframe.sensor_origin =
      report.pose.position + report.pose.orientation * scan.geometry->mount.translation();
  keyframe.points = std::move(report.added_points);
  return keyframe;
}

// The offline variant's products: every valid point of the posed scan into the cloud, and a
// keyframe's full scan into the OctoMap (ray-casting every scan would cost more than the matching).
void VehicleSlam::add_dense(const Scan& scan, const Pose& pose, const SweepMotion& sweep,
                            const Vec3* sensor_origin) {
  if (cloud_) {
    const auto started = Clock::now();
    cloud_->add_scan(scan, pose, sweep);
    cloud_seconds_ += seconds_since(started);
  }
  if (!occupancy_ || !sensor_origin) return;
  const auto started = Clock::now();
  Points points = project_scan(scan, pose.orientation, sweep).points;
  for (Vec3& p : points) p += pose.position;
  occupancy_->insert_keyframe(points, *sensor_origin);
  occupancy_seconds_ += seconds_since(started);
}

// The pipeline turned its map onto the source's heading (icp.heading_anchor): the keyframe poses,
// the motion prior, and what waited for it, turned alike; then the waiting keyframes go to the
// back end and the scans into the dense products.
void VehicleSlam::turn_frame(const FrameTurn& turn) {
  const Eigen::Isometry3d moved = turn.transform();
  const backend::MapCorrection correction{moved, turn.yaw};
  for (backend::NodePose& pose : keyframe_poses_) pose = correction(pose);
  if (inertial_) inertial_->reanchor(moved);
  const Eigen::Matrix2d r = moved.linear().topLeftCorner<2, 2>();
  for (GraphKeyframe& keyframe : unsettled_keyframes_) {
    keyframe.pose = correction(keyframe.pose);
    for (Vec3& p : keyframe.points) p = moved * p;
    for (Vec3& n : keyframe.normals) n = moved.linear() * n;
    keyframe.unseen = r * keyframe.unseen * r.transpose();
    graph_->add(std::move(keyframe));
  }
  unsettled_keyframes_.clear();
  for (UnsettledScan& held : unsettled_scans_) {
    held.pose.position = moved * held.pose.position;
    held.pose.orientation = yaw_rotation(turn.yaw) * held.pose.orientation;
    held.sweep.velocity = yaw_rotation(turn.yaw) * held.sweep.velocity;
    if (held.sensor_origin) held.sensor_origin = moved * *held.sensor_origin;
    add_dense(held.scan, held.pose, held.sweep,
              held.sensor_origin ? &*held.sensor_origin : nullptr);
  }
  unsettled_scans_.clear();
}

// The keyframe, with the points (and normals) it added to the map, to the back end.
void VehicleSlam::add_to_graph(const ScanReport& report) {
  const WorldMap& map = pipeline_.map();
  const std::size_t first = pipeline_.keyframe_starts().back();
  keyframe_poses_.push_back(backend::node_of(report.pose));
  // The motion prior's covariance along what the scan left blind: the graph's step is as unsure.
  const Eigen::Matrix3d blind = Eigen::Matrix3d::Identity() - report.seen.observed;
  const Eigen::Matrix2d unseen =
      (blind * report.covariance * blind.transpose()).topLeftCorner<2, 2>();
  GraphKeyframe keyframe{keyframe_poses_.back(), report.added_points, {}, frame_, {}, unseen};
  if (!map.normals().empty()) {
    keyframe.normals.assign(map.normals().begin() + static_cast<std::ptrdiff_t>(first),
                            map.normals().end());
  }
  // The drift the heading checks learnt, applied to the keyframes made before (one turn at a
  // time: the next is worked out on the headings the last one left).
  if (headings_turned_ == headings_turned_applied_) {
    if (std::optional<std::vector<double>> turns = pipeline_.heading_turns()) {
      keyframe.heading_turns = std::move(*turns);
      ++headings_turned_;
    }
  }
  if (pipeline_.frame_settled()) {
    graph_->add(std::move(keyframe));
  } else {
    unsettled_keyframes_.push_back(std::move(keyframe));
  }
}

// The back end's newest update, if there is one: the keyframes it has where the graph puts them,
// those it has not seen yet moved by the same correction, the map rebuilt on them, and the pose
// and the motion prior moved with it.
bool VehicleSlam::apply_graph_update() {
  std::optional<GraphUpdate> update = graph_->take();
  if (!update) return false;
  const backend::MapCorrection& correction = update->correction;
  std::vector<MapKeyframe> keyframes = std::move(update->keyframes);
  for (MapKeyframe& moved : pipeline_.moved_keyframes(correction.transform, keyframes.size())) {
    moved.turn = correction.yaw;
    keyframes.push_back(std::move(moved));
  }
  for (std::size_t k = 0; k < update->poses.size() && k < keyframe_poses_.size(); ++k) {
    keyframes[k].turn = wrap_angle(update->poses[k].yaw - keyframe_poses_[k].yaw);
  }
  pipeline_.replace_map(keyframes, correction.transform, correction.yaw);
  if (inertial_) inertial_->reanchor(correction.transform);
  for (std::size_t k = 0; k < keyframe_poses_.size(); ++k) {
    keyframe_poses_[k] =
        k < update->poses.size() ? update->poses[k] : correction(keyframe_poses_[k]);
  }
  frame_ = update->frame;
  headings_turned_applied_ = update->headings_turned;
  return true;
}

std::optional<backend::LoopCounts> VehicleSlam::loops() const {
  if (!graph_) return std::nullopt;
  return graph_->counts();
}

double VehicleSlam::backend_seconds() const {
  return graph_ ? graph_->seconds() + inline_update_seconds_ : 0.0;
}

bool VehicleSlam::finish() {
  // A run that ended before the map's heading settled: what waited goes in as it is.
  if (!unsettled_keyframes_.empty() || !unsettled_scans_.empty()) turn_frame(FrameTurn{});
  if (!graph_ || keyframes_ == 0) return false;
  graph_->finish();
  const auto applying = Clock::now();
  apply_graph_update();
  inline_update_seconds_ += seconds_since(applying);
  final_poses_ = graph_->poses();
  return true;
}

Pose VehicleSlam::smoothed(const Pose& pose, const ScanAnchor& anchor) const {
  if (anchor.keyframe >= final_poses_.size()) return pose;
  const backend::NodePose now = backend::compose(final_poses_[anchor.keyframe], anchor.offset);
  Pose moved = pose;
  moved.position = now.position;
  moved.orientation = yaw_rotation(now.yaw - heading_of(pose.orientation)) * pose.orientation;
  return moved;
}

}  // namespace uavslam
