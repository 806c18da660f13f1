#include "dds/MatcherMessages.hpp"

#include <algorithm>

#include "core/Angles.hpp"

namespace uavslam::dds {

float pose_quality(const ScanReport& report, const SlamConfig& config) {
  if (report.outcome == ScanOutcome::MapInitialised) return 1.0f;
  if (!report.accepted()) return 0.0f;
  return static_cast<float>(
      std::clamp(1.0 - report.error_after / config.icp.max_error_after, kLeastMatchQuality, 1.0));
}

msg::PoseWithCovarianceStamped pose_message(const ScanReport& report, const SlamConfig& config,
                                            std::uint64_t scan_seq, std::uint64_t seq,
                                            const Source& source) {
  msg::PoseWithCovarianceStamped m =
      to_msg(report.pose, pose_quality(report, config), scan_seq, seq, source);
  const Eigen::Matrix3d position = report.absolute_covariance();
  if (position.isZero()) return m;
  set_linear_block(m.covariance(), position);
  const double attitude = config.imu.attitude_sigma * config.imu.attitude_sigma;
  m.covariance()[21] = attitude;  // roll
  m.covariance()[28] = attitude;  // pitch
  m.covariance()[35] = config.imu.heading_sigma * config.imu.heading_sigma;
  return m;
}

msg::MapPoints keyframe_message(const Keyframe& keyframe, const Source& source) {
  return to_msg(keyframe.points, keyframe.sensor_origin, keyframe.body, keyframe.index, source);
}

msg::KeyframePoses keyframe_poses_message(const std::vector<backend::NodePose>& poses,
                                          const std::vector<double>& stamps, double stamp,
                                          std::uint64_t correction, const Source& source) {
  msg::KeyframePoses m;
  m.header(make_header(stamp, correction, source));
  m.keyframes().reserve(poses.size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    msg::KeyframePose p;
    p.keyframe_index(static_cast<std::uint32_t>(k));
    p.stamp(to_msg_time(k < stamps.size() ? stamps[k] : 0.0));
    p.position(to_msg(poses[k].position));
    p.yaw(poses[k].yaw);
    m.keyframes().push_back(p);
  }
  return m;
}

std::vector<KeyframePlacement> from_msg(const msg::KeyframePoses& message) {
  std::vector<KeyframePlacement> placements;
  placements.reserve(message.keyframes().size());
  for (const msg::KeyframePose& p : message.keyframes()) {
    placements.push_back(
        {p.keyframe_index(), from_msg_time(p.stamp()), {from_msg(p.position()), p.yaw()}});
  }
  return placements;
}

msg::MatcherStatus status_message(const VehicleScan& result, const Scan& scan, double latency_ms,
                                  const MatcherCounts& counts, std::uint64_t seq,
                                  const Source& source) {
  const ScanReport& report = result.report;
  msg::MatcherStatus s;
  msg::Header header;
  header.stamp(to_msg_time(scan.stamp));
  header.frame_id(source.frame_id);
  header.seq(seq);
  header.vehicle_id(source.vehicle_id);
  s.header(header);
  s.scan_seq(scan.sequence);
  s.outcome(to_string(report.outcome));
  s.iterations(report.iterations);
  s.error_before(report.error_before);
  s.error_after(report.error_after);
  s.points_used(static_cast<std::uint32_t>(report.points_used));
  s.map_updated(report.map_updated);
  s.map_size(report.map_size);
  s.latency_ms(latency_ms);
  s.processing_ms(result.pipeline_seconds * 1e3);
  s.scans_received(counts.received);
  s.scans_skipped(counts.skipped);
  s.scans_rejected(counts.rejected);
  s.scans_accepted(counts.accepted);
  s.loops_searched(static_cast<std::uint32_t>(counts.loops.searches));
  s.loops_accepted(static_cast<std::uint32_t>(counts.loops.accepted));
  s.corrections(static_cast<std::uint32_t>(counts.corrections));
  s.tracking(to_string(result.tracking.state));
  s.tracking_reason(to_string(result.tracking.reason));
  s.degenerate_directions(static_cast<std::uint32_t>(report.seen.degenerate));
  s.heading_drift_deg_per_min(degrees_per_minute(result.heading_drift));
  return s;
}

}  // namespace uavslam::dds
