// Topic names. One vehicle's topics share a prefix so several UAVs can use one DDS domain:
// vehicle "uav1" publishes "uav1/scan", "uav1/pose", ...; with no vehicle id the bare names are
// used. The QoS class of each topic (the <class>_writer / <class>_reader profiles in
// qos/uavslam_profiles.xml) is given beside it.
#pragma once

#include <string>

namespace uavslam::dds {

inline constexpr char kScanTopic[] = "scan";                     // LaserScan, sensor
inline constexpr char kImuTopic[] = "imu";                       // Imu, sensor
inline constexpr char kPoseTopic[] = "pose";                     // PoseWithCovarianceStamped, state
inline constexpr char kMapPointsTopic[] = "map_points";          // MapPoints, map_points
inline constexpr char kMapTopic[] = "map";                       // OccupancyMap, map
inline constexpr char kKeyframePosesTopic[] = "keyframe_poses";  // KeyframePoses, map
inline constexpr char kMatcherStatusTopic[] = "matcher_status";  // MatcherStatus, status
inline constexpr char kOdometryTopic[] = "odom";      // PoseWithCovarianceStamped, sensor
inline constexpr char kVelocityTopic[] = "velocity";  // TwistWithCovarianceStamped, sensor
// `keyframe_poses`: the back end's corrected keyframe poses after a loop (loop_closure.enabled).
// `velocity`: the autopilot's velocity estimate (optical flow, VIO) in the orientation source's
// frame, for the IMU motion prior (motion.fuse_velocity).
// `odom`: wheel odometry, the pose of the scanner (position, heading) in the odometry's own frame
// at the stamp of the scan it belongs to; the Pose type fits it (a stamped position + orientation,
// a covariance slot), quality is 1 and scan_seq the scan's index in a replayed log.

// "<vehicle_id>/<base>" when vehicle_id is non-empty, else base: topic_name("uav1", kScanTopic)
// is "uav1/scan", topic_name("", kScanTopic) is "scan".
inline std::string topic_name(const std::string& vehicle_id, const std::string& base) {
  return vehicle_id.empty() ? base : vehicle_id + "/" + base;
}

}  // namespace uavslam::dds
