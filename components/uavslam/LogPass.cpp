#include "LogPass.hpp"

#include <chrono>
#include <ostream>

#include "common/StopRequest.hpp"
#include "core/Heading.hpp"
#include "core/OdometryPrior.hpp"
#include "core/ScanProjection.hpp"
#include "core/SlamPipeline.hpp"

namespace uavslam::cli {
namespace {

using Clock = std::chrono::steady_clock;

// The pipeline starts where the input says the body is at its first scan.
class Pass {
 public:
  Pass(const PassOptions& options, PassResult& result)
      : options_(options),
        result_(result),
        use_odometry_(options.config.icp.motion_prior == "odometry"),
        odometry_(options.config.imu.max_gap) {
    if (options.cloud_voxel) result.cloud = std::make_unique<DenseCloud>(*options.cloud_voxel);
    if (options.occupancy) result.occupancy = std::make_unique<OccupancyOctree>(*options.occupancy);
  }

  void take(const LogEvent& event) {
    switch (event.kind) {
      case LogEvent::Kind::Imu:
        if (slam_) {
          slam_->add_imu(event.imu);
        } else {
          pending_imu_.push_back(event.imu);
        }
        break;
      case LogEvent::Kind::Odometry:
        if (use_odometry_) odometry_.add(event.odometry);
        break;
      case LogEvent::Kind::Scan:
        take_scan(event);
        break;
    }
  }

  void finish() {
    if (!slam_) return;
    result_.outcomes = slam_->outcome_counts();
    result_.map = slam_->map().points();
  }

 private:
  void start(const LogEvent& event) {
    slam_ =
        std::make_unique<SlamPipeline>(options_.config, event.start_hint.value_or(Vec3::Zero()));
    for (const ImuSample& imu : pending_imu_) slam_->add_imu(imu);
    pending_imu_.clear();
  }

  void take_scan(const LogEvent& event) {
    if (!slam_) start(event);
    const auto started = Clock::now();
    const Vec3 predicted = use_odometry_ ? odometry_.motion_to(event.scan.stamp) : Vec3::Zero();
    const ScanReport report = slam_->process_scan(event.scan, predicted);
    result_.scan_ms.push_back(
        std::chrono::duration<double, std::milli>(Clock::now() - started).count());
    if (report.accepted() || report.dead_reckoned) {
      if (use_odometry_) odometry_.scan_posed(event.scan.stamp);
      add_dense(event.scan, report);
      Pose pose = report.pose;
      pose.stamp = event.output_stamp;
      result_.posed.push_back({event.output_stamp, pose, event.truth, report.dead_reckoned});
    }
    ++result_.scans_in;
    result_.keyframes += report.map_updated;
    result_.dead_reckoned += report.dead_reckoned;
  }

  // The offline variant's products: every valid point of the posed scan into the cloud, and a
  // keyframe's into the OctoMap (ray-casting every scan would cost more than the matching).
  void add_dense(const Scan& scan, const ScanReport& report) {
    if (result_.cloud) {
      const auto started = Clock::now();
      result_.cloud->add_scan(scan, report.pose);
      result_.cloud_seconds += seconds_since(started);
    }
    if (!result_.occupancy || !report.map_updated) return;
    const auto started = Clock::now();
    Points points = project_scan(scan, report.pose.orientation).points;
    for (Vec3& p : points) p += report.pose.position;
    const Vec3 sensor =
        report.pose.position + report.pose.orientation * scan.geometry->mount.translation();
    result_.occupancy->insert_keyframe(points, sensor);
    result_.occupancy_seconds += seconds_since(started);
  }

  static double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

  const PassOptions& options_;
  PassResult& result_;
  bool use_odometry_;
  OdometryPrior odometry_;
  std::unique_ptr<SlamPipeline> slam_;
  std::vector<ImuSample> pending_imu_;  // IMU samples before the first scan, until it comes
};

}  // namespace

std::vector<Pose> PassResult::estimate() const {
  std::vector<Pose> poses;
  poses.reserve(posed.size());
  for (const PosedScan& s : posed) poses.push_back(s.pose);
  return poses;
}

double PassResult::pipeline_seconds() const {
  double ms = 0.0;
  for (double m : scan_ms) ms += m;
  return ms / 1e3;
}

std::vector<eval::PlanarStamped> PassResult::planar_estimate() const {
  std::vector<eval::PlanarStamped> poses;
  poses.reserve(posed.size());
  for (const PosedScan& s : posed) {
    poses.push_back(
        {s.output_stamp, s.pose.position.x(), s.pose.position.y(), heading_of(s.pose.orientation)});
  }
  return poses;
}

std::vector<Pose> PassResult::ground_truth() const {
  std::vector<Pose> poses;
  for (const PosedScan& s : posed) {
    if (s.truth) poses.push_back(*s.truth);
  }
  return poses;
}

PassResult run_pass(LogInput& input, const PassOptions& options, ProgressBar* progress,
                    std::ostream* problems) {
  PassResult result;
  Pass pass(options, result);
  const auto started = Clock::now();
  while (std::optional<LogEvent> event = input.next()) {
    if (process::stop_requested()) {
      result.stopped_early = true;
      break;
    }
    pass.take(*event);
    if (event->kind != LogEvent::Kind::Scan) continue;
    if (progress) progress->update(result.scans_in);
    for (std::string& problem : input.take_problems()) {
      if (problems) *problems << "skipped " << problem << "\n";
      result.problems.push_back(std::move(problem));
    }
  }
  pass.finish();
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
  result.data_seconds = input.data_seconds();
  result.malformed = input.malformed();
  result.input_damage = input.damage();
  if (progress) progress->finish(result.scans_in);
  return result;
}

}  // namespace uavslam::cli
