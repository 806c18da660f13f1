#include "LogPass.hpp"

#include <chrono>
#include <ostream>

#include "common/StopRequest.hpp"
#include "core/Heading.hpp"
#include "slam/VehicleSlam.hpp"

namespace uavslam::cli {
namespace {

using Clock = std::chrono::steady_clock;

// The vehicle's SLAM over the input's events; the map starts where the input says the body is at
// its first scan.
class Pass {
 public:
  Pass(const PassOptions& options, PassResult& result)
      : result_(result), slam_(options.config, options.products) {}

  void take(const LogEvent& event) {
    switch (event.kind) {
      case LogEvent::Kind::Imu:
        slam_.add_imu(event.imu);
        break;
      case LogEvent::Kind::Odometry:
        slam_.add_odometry(event.odometry);
        break;
      case LogEvent::Kind::Velocity:
        slam_.add_velocity(event.velocity);
        break;
      case LogEvent::Kind::Scan:
        take_scan(event);
        break;
    }
  }

  void finish() {
    // The back end's last word: the graph optimised once more, every posed scan moved with the
    // keyframe it was made after, the map rebuilt on the keyframes.
    if (slam_.finish()) {
      for (std::size_t i = 0; i < result_.posed.size(); ++i) {
        if (!anchors_[i]) continue;
        const double stamp = result_.posed[i].pose.stamp;
        result_.posed[i].pose = slam_.smoothed(result_.posed[i].pose, *anchors_[i]);
        result_.posed[i].pose.stamp = stamp;
      }
    }
    result_.loops = slam_.loops();
    result_.backend_seconds = slam_.backend_seconds();
    result_.outcomes = slam_.pipeline().outcome_counts();
    result_.map = slam_.pipeline().map().points();
    result_.keyframes = slam_.keyframes();
    result_.cloud = slam_.take_cloud();
    result_.occupancy = slam_.take_occupancy();
    result_.cloud_seconds = slam_.cloud_seconds();
    result_.occupancy_seconds = slam_.occupancy_seconds();
  }

 private:
  void take_scan(const LogEvent& event) {
    if (result_.scans_in == 0) slam_.start_at(event.start_hint.value_or(Vec3::Zero()));
    const VehicleScan scan = slam_.process_scan(event.scan);
    result_.scan_ms.push_back(scan.pipeline_seconds * 1e3);
    if (scan.posed()) {
      Pose pose = scan.report.pose;
      pose.stamp = event.output_stamp;
      result_.posed.push_back({event.output_stamp, pose, event.truth, scan.report.dead_reckoned});
      anchors_.push_back(scan.anchor);
    }
    ++result_.scans_in;
    result_.dead_reckoned += scan.report.dead_reckoned;
    result_.yaw_held += scan.report.yaw_held;
    result_.moving_points += scan.report.moving_points;
    result_.scans_with_moving_points += scan.report.moving_points > 0;
    result_.tracking.add(scan.tracking);
  }

  PassResult& result_;
  VehicleSlam slam_;
  std::vector<std::optional<ScanAnchor>> anchors_;  // one per posed scan
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
  result.no_return_code = input.no_return_code();
  if (progress) progress->finish(result.scans_in);
  return result;
}

}  // namespace uavslam::cli
