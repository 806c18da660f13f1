#include "dds/Conversions.hpp"

#include <cmath>

#include "core/Heading.hpp"

namespace uavslam::dds {

msg::Header make_header(double stamp, std::uint64_t seq, const Source& source) {
  msg::Header header;
  header.stamp(to_msg_time(stamp));
  header.seq(seq);
  header.frame_id(source.frame_id);
  header.vehicle_id(source.vehicle_id);
  return header;
}

msg::Vector3 to_msg(const Vec3& v) {
  msg::Vector3 m;
  m.x(v.x());
  m.y(v.y());
  m.z(v.z());
  return m;
}

Vec3 from_msg(const msg::Vector3& m) {
  return {m.x(), m.y(), m.z()};
}

namespace {

msg::Quaternion to_msg(const Eigen::Quaterniond& q) {
  msg::Quaternion m;
  m.x(q.x());
  m.y(q.y());
  m.z(q.z());
  m.w(q.w());
  return m;
}

Eigen::Quaterniond from_msg(const msg::Quaternion& m) {
  return {m.w(), m.x(), m.y(), m.z()};
}

}  // namespace

msg::Time to_msg_time(double seconds) {
  double whole = std::floor(seconds);
  auto nanosec = static_cast<std::int64_t>(std::llround((seconds - whole) * 1e9));
  if (nanosec >= 1000000000) {
    whole += 1.0;
    nanosec -= 1000000000;
  }
  msg::Time time;
  time.sec(static_cast<std::int32_t>(whole));
  time.nanosec(static_cast<std::uint32_t>(nanosec));
  return time;
}

double from_msg_time(const msg::Time& time) {
  return time.sec() + time.nanosec() * 1e-9;
}

msg::LaserScan to_msg(const Scan& scan, double angle_min, double angle_increment,
                      const Source& source) {
  msg::LaserScan m;
  m.header(make_header(scan.stamp, scan.sequence, source));
  m.angle_min(static_cast<float>(angle_min));
  m.angle_increment(static_cast<float>(angle_increment));
  const auto beams = static_cast<double>(scan.ranges.size());
  m.angle_max(static_cast<float>(angle_min + (beams - 1.0) * angle_increment));
  if (scan.geometry) {
    m.range_min(static_cast<float>(scan.geometry->min_range));
    m.range_max(static_cast<float>(scan.geometry->max_range));
    // Beams fired in order at a steady rate: the step between the first two.
    const std::vector<double>& fired = scan.geometry->fire_times;
    if (fired.size() > 1) m.time_increment(static_cast<float>(fired[1] - fired[0]));
  }
  m.ranges(scan.ranges);
  m.intensities(scan.intensities);
  return m;
}

Scan from_msg(const msg::LaserScan& message, std::shared_ptr<const ScanGeometry> geometry) {
  Scan scan;
  scan.stamp = from_msg_time(message.header().stamp());
  scan.sequence = message.header().seq();
  scan.geometry = std::move(geometry);
  scan.ranges = message.ranges();
  scan.intensities = message.intensities();
  return scan;
}

msg::Imu to_msg(const ImuSample& sample, std::uint64_t seq, const Source& source) {
  msg::Imu m;
  m.header(make_header(sample.stamp, seq, source));
  m.orientation(to_msg(sample.orientation));
  m.angular_velocity(to_msg(sample.angular_velocity));
  m.linear_acceleration(to_msg(sample.linear_acceleration));
  return m;
}

ImuSample from_msg(const msg::Imu& message) {
  ImuSample sample;
  sample.stamp = from_msg_time(message.header().stamp());
  sample.orientation = from_msg(message.orientation());
  sample.angular_velocity = from_msg(message.angular_velocity());
  sample.linear_acceleration = from_msg(message.linear_acceleration());
  return sample;
}

void set_linear_block(std::array<double, 36>& covariance, const Eigen::Matrix3d& block) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) covariance[static_cast<std::size_t>(6 * r + c)] = block(r, c);
  }
}

Eigen::Matrix3d linear_block(const std::array<double, 36>& covariance) {
  Eigen::Matrix3d block;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) block(r, c) = covariance[static_cast<std::size_t>(6 * r + c)];
  }
  return block;
}

msg::TwistWithCovarianceStamped to_msg(const VelocitySample& sample, std::uint64_t seq,
                                       const Source& source) {
  msg::TwistWithCovarianceStamped m;
  m.header(make_header(sample.stamp, seq, source));
  m.linear(to_msg(sample.velocity));
  set_linear_block(m.covariance(), sample.covariance);
  return m;
}

VelocitySample from_msg(const msg::TwistWithCovarianceStamped& message) {
  VelocitySample sample;
  sample.stamp = from_msg_time(message.header().stamp());
  sample.velocity = from_msg(message.linear());
  sample.covariance = linear_block(message.covariance());
  return sample;
}

msg::PoseWithCovarianceStamped to_msg(const Pose& pose, float quality, std::uint64_t scan_seq,
                                      std::uint64_t seq, const Source& source) {
  msg::PoseWithCovarianceStamped m;
  m.header(make_header(pose.stamp, seq, source));
  m.position(to_msg(pose.position));
  m.orientation(to_msg(pose.orientation));
  m.quality(quality);
  m.scan_seq(scan_seq);
  return m;
}

Pose from_msg(const msg::PoseWithCovarianceStamped& message) {
  Pose pose;
  pose.stamp = from_msg_time(message.header().stamp());
  pose.position = from_msg(message.position());
  pose.orientation = from_msg(message.orientation());
  return pose;
}

msg::MapPoints to_msg(const Points& points, const Vec3& sensor_origin, const Pose& body,
                      std::uint32_t keyframe_index, const Source& source) {
  msg::MapPoints m;
  m.header(make_header(body.stamp, keyframe_index, source));
  m.keyframe_index(keyframe_index);
  m.sensor_origin(to_msg(sensor_origin));
  m.body_position(to_msg(body.position));
  m.body_yaw(heading_of(body.orientation));
  m.points().reserve(points.size());
  for (const Vec3& p : points) {
    msg::Point32 q;
    q.x(static_cast<float>(p.x()));
    q.y(static_cast<float>(p.y()));
    q.z(static_cast<float>(p.z()));
    m.points().push_back(q);
  }
  return m;
}

Points from_msg(const msg::MapPoints& message) {
  Points points;
  points.reserve(message.points().size());
  for (const msg::Point32& p : message.points()) points.emplace_back(p.x(), p.y(), p.z());
  return points;
}

}  // namespace uavslam::dds
