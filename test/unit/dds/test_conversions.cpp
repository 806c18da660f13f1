#include <limits>

#include <gtest/gtest.h>

#include "dds/Conversions.hpp"

namespace uavslam::dds {
namespace {

const Source kSource{"laser", "uav1"};

TEST(Conversions, TimeKeepsNanoseconds) {
  const msg::Time t = to_msg_time(1700000000.123456789);
  EXPECT_EQ(t.sec(), 1700000000);
  EXPECT_NEAR(double(t.nanosec()), 123456789.0, 300.0);  // a double holds ~0.2 us here
  EXPECT_EQ(to_msg_time(12.5).nanosec(), 500000000u);
  EXPECT_EQ(to_msg_time(2.9999999999).sec(), 3);  // rounds up into the next second
  EXPECT_EQ(to_msg_time(2.9999999999).nanosec(), 0u);
  EXPECT_EQ(to_msg_time(-0.25).sec(), -1);
  EXPECT_EQ(to_msg_time(-0.25).nanosec(), 750000000u);
  EXPECT_DOUBLE_EQ(from_msg_time(to_msg_time(42.125)), 42.125);
}

TEST(Conversions, ScanRoundTripsWithTheReceiversGeometry) {
  auto geometry = std::make_shared<ScanGeometry>(ScanGeometry::planar(-1.0, 0.5, 5));
  geometry->min_range = 0.2;
  geometry->max_range = 20.0;
  Scan scan;
  scan.stamp = 10.025;
  scan.sequence = 401;
  scan.geometry = geometry;
  scan.ranges = {1.0f, 2.0f, std::numeric_limits<float>::infinity(), 4.0f, 5.0f};
  const msg::LaserScan m = to_msg(scan, -1.0, 0.5, kSource);
  EXPECT_FLOAT_EQ(m.angle_max(), 1.0f);
  EXPECT_FLOAT_EQ(m.range_min(), 0.2f);
  EXPECT_EQ(m.header().seq(), 401u);
  EXPECT_EQ(m.header().frame_id(), "laser");
  const Scan back = from_msg(m, geometry);
  EXPECT_NEAR(back.stamp, 10.025, 1e-9);
  EXPECT_EQ(back.sequence, 401u);
  EXPECT_EQ(back.ranges, scan.ranges);
  EXPECT_EQ(back.geometry, geometry);
}

TEST(Conversions, ImuRoundTrips) {
  ImuSample s;
  s.stamp = 3.005;
  s.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
  s.angular_velocity = Vec3(0.1, -0.2, 0.3);
  s.linear_acceleration = Vec3(0.5, 0.0, 9.8);
  const ImuSample back = from_msg(to_msg(s, 7, kSource));
  EXPECT_NEAR(back.stamp, s.stamp, 1e-9);
  EXPECT_TRUE(back.orientation.isApprox(s.orientation, 1e-12));
  EXPECT_EQ(back.angular_velocity, s.angular_velocity);
  EXPECT_EQ(back.linear_acceleration, s.linear_acceleration);
}

// The velocity and its covariance (the 6x6's linear block; the angular part left zero).
TEST(Conversions, VelocityRoundTrips) {
  VelocitySample v;
  v.stamp = 12.25;
  v.velocity = Vec3(1.0, -0.5, 0.1);
  v.covariance << 0.01, 0.001, 0.0, 0.001, 0.02, 0.0, 0.0, 0.0, 0.03;
  const msg::TwistWithCovarianceStamped m = to_msg(v, 5, kSource);
  EXPECT_EQ(m.covariance()[7], 0.02);  // row 1, column 1 of the 6x6
  EXPECT_EQ(m.covariance()[21], 0.0);  // the angular block: unknown
  const VelocitySample back = from_msg(m);
  EXPECT_NEAR(back.stamp, v.stamp, 1e-9);
  EXPECT_EQ(back.velocity, v.velocity);
  EXPECT_EQ(back.covariance, v.covariance);
}

TEST(Conversions, PoseRoundTrips) {
  Pose p;
  p.stamp = 100.5;
  p.position = Vec3(3, -2, 1.5);
  p.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Vec3::UnitZ()));
  const msg::PoseWithCovarianceStamped m = to_msg(p, 0.9f, 4020, 11, kSource);
  EXPECT_EQ(m.scan_seq(), 4020u);
  EXPECT_FLOAT_EQ(m.quality(), 0.9f);
  const Pose back = from_msg(m);
  EXPECT_NEAR(back.stamp, p.stamp, 1e-9);
  EXPECT_EQ(back.position, p.position);
  EXPECT_TRUE(back.orientation.isApprox(p.orientation, 1e-12));
}

TEST(Conversions, MapPointsRoundTripInFloatPrecision) {
  const Points points = {Vec3(1.25, 2.5, 0.75), Vec3(-19.999, 14.001, 3.999)};
  Pose body;
  body.stamp = 5.0;
  body.position = Vec3(1, 1, 1.5);
  body.orientation = Eigen::AngleAxisd(-1.2, Vec3::UnitZ());
  const msg::MapPoints m = to_msg(points, Vec3(1, 1, 1.6), body, 3, kSource);
  EXPECT_EQ(m.keyframe_index(), 3u);
  EXPECT_EQ(m.sensor_origin().z(), 1.6);
  EXPECT_EQ(from_msg(m.body_position()), body.position);
  EXPECT_NEAR(m.body_yaw(), -1.2, 1e-12);
  EXPECT_NEAR(from_msg_time(m.header().stamp()), 5.0, 1e-9);
  const Points back = from_msg(m);
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_LT((back[i] - points[i]).norm(), 1e-5);
}

}  // namespace
}  // namespace uavslam::dds
