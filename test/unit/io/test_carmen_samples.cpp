// The one adapter from a CARMEN laser line to a vehicle's inputs: the robot's samples for the log
// tools, the laser's for scans that travel without their mount.
#include <cmath>

#include <gtest/gtest.h>

#include "core/Heading.hpp"
#include "io/CarmenSamples.hpp"

namespace uavslam::io {
namespace {

// FR079's geometry: the laser 0.04 m behind the odometry centre, on the same heading.
TimedCarmenScan fr079_like_scan(double stamp, std::size_t index) {
  TimedCarmenScan timed;
  timed.stamp = stamp;
  timed.index = index;
  CarmenScan& scan = timed.scan;
  scan.ipc_timestamp = stamp + 100.0;
  scan.start_angle = -M_PI / 2;
  scan.angle_increment = M_PI / 180;
  scan.ranges.assign(180, 2.0f);
  scan.robot_pose = {1.0, 2.0, 0.5};
  scan.laser_pose = {1.0 - 0.04 * std::cos(0.5), 2.0 - 0.04 * std::sin(0.5), 0.5};
  return timed;
}

TEST(CarmenSensor, TheRobotsSamplesCarryTheLasersMountInTheScan) {
  CarmenSensor sensor(CarmenBody::Robot);
  const CarmenSamples s = sensor.samples_of(fr079_like_scan(3.0, 7));
  EXPECT_EQ(s.orientation.stamp, 3.0);
  EXPECT_NEAR(heading_of(s.orientation.orientation), 0.5, 1e-12);
  EXPECT_EQ(s.orientation.angular_velocity, Vec3::Zero());
  EXPECT_EQ(s.odometry.stamp, 3.0);
  EXPECT_EQ(s.odometry.position, Vec3(1.0, 2.0, 0.0));
  EXPECT_EQ(s.scan.stamp, 3.0) << "the timeline stamp, not ipc_timestamp";
  EXPECT_EQ(s.scan.sequence, 7u);
  ASSERT_TRUE(s.scan.geometry);
  EXPECT_EQ(s.scan.geometry->directions.size(), 180u);
  EXPECT_NEAR(s.scan.geometry->mount.translation().x(), -0.04, 1e-9);
}

TEST(CarmenSensor, TheLasersSamplesPutTheLaserAtTheBodyOrigin) {
  CarmenSensor sensor(CarmenBody::Laser);
  const TimedCarmenScan timed = fr079_like_scan(3.0, 7);
  const CarmenSamples s = sensor.samples_of(timed);
  EXPECT_EQ(s.odometry.position, Vec3(timed.scan.laser_pose.x, timed.scan.laser_pose.y, 0.0));
  EXPECT_TRUE(s.scan.geometry->mount.isApprox(Eigen::Isometry3d::Identity()));
}

TEST(CarmenSensor, OneGeometryPerLayoutAndAHeadingOffsetOnRequest) {
  CarmenSensor sensor(CarmenBody::Robot);
  const CarmenSamples first = sensor.samples_of(fr079_like_scan(1.0, 0));
  const CarmenSamples second = sensor.samples_of(fr079_like_scan(1.1, 1), 0.25);
  EXPECT_EQ(first.scan.geometry, second.scan.geometry);
  EXPECT_NEAR(heading_of(second.orientation.orientation), 0.75, 1e-12);
  TimedCarmenScan wider = fr079_like_scan(1.2, 2);
  wider.scan.ranges.assign(361, 2.0f);
  EXPECT_NE(sensor.samples_of(wider).scan.geometry, first.scan.geometry);
}

}  // namespace
}  // namespace uavslam::io
