// Every wire type survives CDR serialisation unchanged: what a publisher fills in is what a
// subscriber reads, field by field (the generated operator== compares every member).
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

#include <msg/ImuPubSubTypes.h>
#include <msg/KeyframePosesPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/MapPointsPubSubTypes.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/OccupancyMapPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <msg/TwistPubSubTypes.h>

namespace uavslam::msg {
namespace {

template <typename PubSubType>
typename PubSubType::type round_trip(typename PubSubType::type& sample) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&sample)());
  EXPECT_TRUE(type.serialize(&sample, &payload));
  typename PubSubType::type received;
  EXPECT_TRUE(type.deserialize(&payload, &received));
  return received;
}

Header header(std::uint64_t seq) {
  Time stamp;
  stamp.sec(1700000000);
  stamp.nanosec(123456789);
  Header h;
  h.stamp(stamp);
  h.frame_id("laser");
  h.seq(seq);
  h.vehicle_id("uav7");
  return h;
}

Vector3 vector(double x, double y, double z) {
  Vector3 v;
  v.x(x);
  v.y(y);
  v.z(z);
  return v;
}

TEST(WireTypes, LaserScanRoundTrips) {
  LaserScan scan;
  scan.header(header(41));
  scan.angle_min(-2.356f);
  scan.angle_max(2.356f);
  scan.angle_increment(0.004363f);
  scan.time_increment(1.7e-5f);
  scan.scan_time(0.025f);
  scan.range_min(0.1f);
  scan.range_max(30.0f);
  for (int i = 0; i < 1080; ++i) scan.ranges().push_back(0.5f + 0.01f * float(i));
  scan.ranges()[3] = std::numeric_limits<float>::infinity();
  scan.intensities().assign(1080, 7.0f);
  const LaserScan received = round_trip<LaserScanPubSubType>(scan);
  EXPECT_EQ(received, scan);
  EXPECT_EQ(received.ranges().size(), 1080u);
  EXPECT_EQ(received.header().vehicle_id(), "uav7");
}

TEST(WireTypes, ImuRoundTrips) {
  Imu imu;
  imu.header(header(9));
  Quaternion q;
  q.x(0.1);
  q.y(-0.2);
  q.z(0.3);
  q.w(0.927);
  imu.orientation(q);
  imu.orientation_covariance()[0] = 1e-4;
  imu.orientation_covariance()[8] = 3e-4;
  imu.angular_velocity(vector(0.01, -0.02, 0.5));
  imu.angular_velocity_covariance()[4] = 2e-6;
  imu.linear_acceleration(vector(0.1, 0.2, 9.81));
  imu.linear_acceleration_covariance()[0] = -1.0;
  EXPECT_EQ(round_trip<ImuPubSubType>(imu), imu);
}

TEST(WireTypes, PoseRoundTrips) {
  PoseWithCovarianceStamped pose;
  pose.header(header(100));
  pose.position(vector(3.5, -1.25, 1.5));
  Quaternion q;
  q.w(1.0);
  pose.orientation(q);
  for (std::size_t i = 0; i < 36; ++i) pose.covariance()[i] = double(i) * 1e-3;
  pose.quality(0.87f);
  pose.scan_seq(99);
  EXPECT_EQ(round_trip<PoseWithCovarianceStampedPubSubType>(pose), pose);
}

TEST(WireTypes, TwistRoundTrips) {
  TwistWithCovarianceStamped twist;
  twist.header(header(21));
  twist.linear(vector(0.8, -0.1, 0.05));
  twist.angular(vector(0.0, 0.0, 0.3));
  for (std::size_t i = 0; i < 36; ++i) twist.covariance()[i] = double(i) * 1e-4;
  EXPECT_EQ(round_trip<TwistWithCovarianceStampedPubSubType>(twist), twist);
}

TEST(WireTypes, MapPointsRoundTrips) {
  MapPoints points;
  points.header(header(5));
  points.keyframe_index(5);
  points.sensor_origin(vector(1, 2, 1.6));
  points.body_position(vector(1, 2, 1.5));
  points.body_yaw(-0.75);
  for (int i = 0; i < 216; ++i) {
    Point32 p;
    p.x(float(i));
    p.y(-float(i));
    p.z(0.5f);
    points.points().push_back(p);
  }
  EXPECT_EQ(round_trip<MapPointsPubSubType>(points), points);
}

TEST(WireTypes, KeyframePosesRoundTrip) {
  KeyframePoses poses;
  poses.header(header(3));
  for (std::uint32_t i = 0; i < 500; ++i) {
    KeyframePose p;
    p.keyframe_index(i);
    p.position(vector(0.5 * i, -0.25 * i, 1.2));
    p.yaw(0.01 * i);
    poses.keyframes().push_back(p);
  }
  EXPECT_EQ(round_trip<KeyframePosesPubSubType>(poses), poses);
}

TEST(WireTypes, OccupancyMapRoundTripsAMegabyteTree) {
  OccupancyMap map;
  map.header(header(2));
  map.map_seq(2);
  map.resolution(0.05);
  map.min_bound(vector(0, 0, 0));
  map.max_bound(vector(20, 15, 4));
  map.occupied_cells(12345);
  map.map_points(54000);
  map.octomap_binary().resize(1 << 20);
  for (std::size_t i = 0; i < map.octomap_binary().size(); ++i) {
    map.octomap_binary()[i] = static_cast<std::uint8_t>(i * 31);
  }
  EXPECT_EQ(round_trip<OccupancyMapPubSubType>(map), map);
}

TEST(WireTypes, MatcherStatusRoundTrips) {
  MatcherStatus status;
  status.header(header(77));
  status.scan_seq(77);
  status.outcome("error_increased");
  status.iterations(10);
  status.error_before(0.0031);
  status.error_after(0.0042);
  status.points_used(216);
  status.map_updated(true);
  status.map_size(54000);
  status.latency_ms(1.25);
  status.processing_ms(0.46);
  status.scans_received(78);
  status.scans_skipped(1);
  status.scans_rejected(3);
  status.scans_accepted(74);
  EXPECT_EQ(round_trip<MatcherStatusPubSubType>(status), status);
}

}  // namespace
}  // namespace uavslam::msg
