// Between the wire types (idl/, generated) and the core's types. The only place that knows both.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include <msg/Imu.h>
#include <msg/LaserScan.h>
#include <msg/MapPoints.h>
#include <msg/Pose.h>
#include <msg/Twist.h>

#include "core/Types.hpp"

namespace uavslam::dds {

// Who published: the header fields that are not the data's own.
struct Source {
  std::string frame_id;
  std::string vehicle_id;
};

// A header stamped `stamp` (s) with this sequence number and source.
msg::Header make_header(double stamp, std::uint64_t seq, const Source& source);
msg::Vector3 to_msg(const Vec3& v);
Vec3 from_msg(const msg::Vector3& m);

// Seconds as a double <-> (sec, nanosec), rounded to the nearest nanosecond.
msg::Time to_msg_time(double seconds);
double from_msg_time(const msg::Time& time);

// A planar scan's beam i is at angle_min + i * angle_increment (sensor_msgs/LaserScan).
msg::LaserScan to_msg(const Scan& scan, double angle_min, double angle_increment,
                      const Source& source);
// The receiver knows the sensor (mount, mirror): it supplies the geometry the ranges belong to.
// A range count that differs from the geometry is kept as it is; the pipeline drops such a scan
// as malformed and counts it.
Scan from_msg(const msg::LaserScan& message, std::shared_ptr<const ScanGeometry> geometry);

msg::Imu to_msg(const ImuSample& sample, std::uint64_t seq, const Source& source);
ImuSample from_msg(const msg::Imu& message);

// The upper-left 3x3 block of a row-major 6x6 covariance (the linear part: position, velocity),
// written into it and read from it.
void set_linear_block(std::array<double, 36>& covariance, const Eigen::Matrix3d& block);
Eigen::Matrix3d linear_block(const std::array<double, 36>& covariance);

// The linear velocity and its covariance (the 6x6's upper-left block); the angular part zero.
msg::TwistWithCovarianceStamped to_msg(const VelocitySample& sample, std::uint64_t seq,
                                       const Source& source);
VelocitySample from_msg(const msg::TwistWithCovarianceStamped& message);

// quality: 0 (lost) .. 1; scan_seq: the scan the pose came from.
msg::PoseWithCovarianceStamped to_msg(const Pose& pose, float quality, std::uint64_t scan_seq,
                                      std::uint64_t seq, const Source& source);
Pose from_msg(const msg::PoseWithCovarianceStamped& message);

// body: the keyframe's body pose (its position and heading), where the points were placed from.
msg::MapPoints to_msg(const Points& points, const Vec3& sensor_origin, const Pose& body,
                      std::uint32_t keyframe_index, const Source& source);
Points from_msg(const msg::MapPoints& message);

}  // namespace uavslam::dds
