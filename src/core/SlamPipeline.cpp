#include "core/SlamPipeline.hpp"

#include <cmath>

#include "core/ScanProjection.hpp"

namespace uavslam {
namespace {

// A translation in three unknowns needs at least this many pairs to be more than a guess.
constexpr std::size_t kMinPoints = 10;

bool is_well_formed(const Scan& scan) {
  return scan.geometry && std::isfinite(scan.stamp) &&
         scan.ranges.size() == scan.geometry->directions.size() && !scan.ranges.empty();
}

}  // namespace

SlamPipeline::SlamPipeline(const SlamConfig& config, const Vec3& initial_position)
    : config_(config),
      imu_(config.imu.max_gap),
      map_(make_nearest_neighbour_index(config.nearest_neighbour)),
      matcher_(config.icp) {
  pose_.position = initial_position;
}

void SlamPipeline::add_imu(const ImuSample& sample) {
  imu_.add(sample);
}

ScanReport SlamPipeline::process_scan(const Scan& scan, const Vec3& predicted_motion) {
  ScanReport report;
  report.pose = pose_;
  if (!is_well_formed(scan)) return finish(report);

  // Step 1: orientation at the scan's time, points into the world orientation.
  const auto orientation = imu_.orientation_at(scan.stamp);
  if (!orientation) {
    report.outcome = ScanOutcome::NoImu;
    return finish(report);
  }
  ProjectedScan projected = project_scan(scan, *orientation);
  report.invalid_ranges = projected.invalid;
  // Step 2: every k-th point.
  const int k = config_.scan.subsample_every;
  const ScanPoints points =
      weigh_points(keep_every_kth(projected.points, k), keep_every_kth(projected.vertical, k),
                   config_.icp.split_axes);
  report.points_used = points.points.size();
  if (report.points_used < kMinPoints) {
    report.outcome = ScanOutcome::TooFewPoints;
    return finish(report);
  }

  const Pose candidate{scan.stamp, pose_.position, *orientation};
  if (map_.empty()) {
    // The first scan seeds the map where the vehicle starts.
    pose_ = candidate;
    report.outcome = ScanOutcome::MapInitialised;
    report.pose = pose_;
    add_to_map(report, projected.points);
    return finish(report);
  }

  // Steps 3-5: translation-only ICP from the last position (the seed) moved by the prediction.
  // The matcher measures its correction, and so the seed's 1 m "distance moved" check, from this
  // start: the check limits what the matcher changed, not the predicted motion itself.
  const MatchResult match = matcher_.match(map_, points, pose_.position + predicted_motion);
  report.outcome = match.outcome;
  report.error_before = match.error_before;
  report.error_after = match.error_after;
  report.iterations = match.iterations;
  if (match.outcome != ScanOutcome::Accepted) return finish(report);

  // Steps 6-7: report the new position (orientation from the IMU); a keyframe after enough motion.
  pose_ = {scan.stamp, match.position, *orientation};
  report.pose = pose_;
  if (moved_enough_for_map_update(pose_.position)) add_to_map(report, projected.points);
  return finish(report);
}

ScanReport SlamPipeline::finish(ScanReport report) {
  ++counts_[static_cast<std::size_t>(report.outcome)];
  report.map_size = map_.size();
  return report;
}

// Seed step 5: "+-0.2 m height and 0.5 m laterally" since the last map update.
bool SlamPipeline::moved_enough_for_map_update(const Vec3& position) const {
  const Vec3 moved = position - last_map_update_position_;
  return std::abs(moved.z()) > config_.map.keyframe_height ||
         moved.head<2>().norm() > config_.map.keyframe_lateral;
}

// Step 5: the aligned scan, thinned to every k-th point, into the map at the new position.
void SlamPipeline::add_to_map(ScanReport& report, const Points& projected) {
  Points aligned = keep_every_kth(projected, config_.map.subsample_every);
  apply_transform(aligned, pose_.position);
  map_.add_points(aligned);
  last_map_update_position_ = pose_.position;
  report.map_updated = true;
  report.added_points = std::move(aligned);
}

}  // namespace uavslam
