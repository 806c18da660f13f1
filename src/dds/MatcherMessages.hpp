// What the matcher publishes for one scan, from what the vehicle's SLAM made of it
// (slam/VehicleSlam): the pose, the keyframe's points and the scan's status.
#pragma once

#include <cstdint>
#include <vector>

#include <msg/KeyframePoses.h>
#include <msg/MapPoints.h>
#include <msg/MatcherStatus.h>
#include <msg/Pose.h>

#include "core/SlamConfig.hpp"
#include "core/SlamPipeline.hpp"
#include "dds/Conversions.hpp"
#include "slam/VehicleSlam.hpp"

namespace uavslam::dds {

// How good the match was, for consumers of `pose`: 1 for a perfect fit, 0.01 at the rejection
// limit (icp.max_error_after); 1 for the scan that seeded the map; 0 for a pose the motion prior
// carried (a rejected scan, dead-reckoned): no scan confirmed it.
float pose_quality(const ScanReport& report, const SlamConfig& config);
inline constexpr double kLeastMatchQuality = 0.01;

// The pose's covariance: the position's as the report gives it, the attitude's as the orientation
// source states it (imu.attitude_sigma, imu.heading_sigma); all zero (unknown) when the report has
// none (the seed's mode, without the degeneracy analysis).
msg::PoseWithCovarianceStamped pose_message(const ScanReport& report, const SlamConfig& config,
                                            std::uint64_t scan_seq, std::uint64_t seq,
                                            const Source& source);

// The header's seq is the keyframe's index.
msg::MapPoints keyframe_message(const Keyframe& keyframe, const Source& source);

// The back end's keyframe poses after a correction (`keyframe_poses`), every keyframe made so
// far in the map's current frame; the header's seq is the correction's number.
// stamps: each keyframe's scan's; stamp: the first scan whose pose is in the corrected frame.
msg::KeyframePoses keyframe_poses_message(const std::vector<backend::NodePose>& poses,
                                          const std::vector<double>& stamps, double stamp,
                                          std::uint64_t correction, const Source& source);
struct KeyframePlacement {
  std::uint32_t index = 0;
  double stamp = 0.0;
  backend::NodePose pose;
};
std::vector<KeyframePlacement> from_msg(const msg::KeyframePoses& message);

// The matcher's running counts, as the status carries them.
struct MatcherCounts {
  std::uint64_t received = 0;
  std::uint64_t skipped = 0;  // dropped unprocessed: a fresher scan was waiting
  std::uint64_t rejected = 0;
  std::uint64_t accepted = 0;     // scans matched
  backend::LoopCounts loops;      // the back end's (none: zeros)
  std::uint64_t corrections = 0;  // keyframe_poses published
};

// latency_ms: from the scan's publication to now; the processing time is the pipeline's.
msg::MatcherStatus status_message(const VehicleScan& result, const Scan& scan, double latency_ms,
                                  const MatcherCounts& counts, std::uint64_t seq,
                                  const Source& source);

}  // namespace uavslam::dds
