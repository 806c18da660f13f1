#include "io/CarmenSamples.hpp"

#include "core/Heading.hpp"

namespace uavslam::io {

CarmenSamples CarmenSensor::samples_of(const TimedCarmenScan& timed, double heading_offset) {
  const CarmenScan& carmen = timed.scan;
  const CarmenPose2& body = body_ == CarmenBody::Robot ? carmen.robot_pose : carmen.laser_pose;
  CarmenSamples samples;
  samples.orientation = {timed.stamp, yaw_rotation(body.theta + heading_offset), Vec3::Zero(),
                         Vec3::Zero()};
  samples.odometry = {timed.stamp, Vec3(body.x, body.y, 0.0)};
  samples.scan = to_core_scan(carmen, geometry_for(carmen), timed.index);
  samples.scan.stamp = timed.stamp;
  return samples;
}

std::shared_ptr<const ScanGeometry> CarmenSensor::geometry_for(const CarmenScan& scan) {
  const Eigen::Isometry3d mount =
      body_ == CarmenBody::Robot ? laser_mount(scan) : Eigen::Isometry3d::Identity();
  if (!geometry_ || scan.ranges.size() != beams_ || scan.start_angle != start_ ||
      scan.angle_increment != increment_ || scan.max_range != max_range_ ||
      !mount.isApprox(geometry_->mount, 0.0)) {
    ScanGeometry geometry = to_scan_geometry(scan);
    geometry.mount = mount;
    geometry_ = std::make_shared<const ScanGeometry>(std::move(geometry));
    beams_ = scan.ranges.size();
    start_ = scan.start_angle;
    increment_ = scan.angle_increment;
    max_range_ = scan.max_range;
  }
  return geometry_;
}

}  // namespace uavslam::io
