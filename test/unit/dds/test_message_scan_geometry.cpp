// The core geometry of a scan message's own beam layout (replayed 2D logs).
#include <cmath>

#include <gtest/gtest.h>

#include "dds/Conversions.hpp"
#include "dds/MessageScanGeometry.hpp"
#include "sensor/LidarGeometry.hpp"

namespace uavslam::dds {
namespace {

constexpr double kPi = 3.14159265358979323846;

msg::LaserScan scan_message(std::size_t beams, float angle_min, float increment) {
  msg::LaserScan m;
  m.angle_min(angle_min);
  m.angle_increment(increment);
  m.range_min(0.1f);
  m.range_max(81.8f);
  m.ranges(std::vector<float>(beams, 1.0f));
  return m;
}

TEST(MessageScanGeometry, APlanarScannerAtTheBodyOriginWithTheMessagesBeams) {
  MessageScanGeometry geometries;
  const auto g = geometries.for_message(
      scan_message(180, static_cast<float>(-kPi / 2), static_cast<float>(kPi / 180)));
  ASSERT_EQ(g->directions.size(), 180u);
  EXPECT_NEAR(g->directions[0].x(), 0.0, 1e-6);
  EXPECT_NEAR(g->directions[0].y(), -1.0, 1e-6);
  EXPECT_NEAR(g->directions[90].x(), 1.0, 1e-6);  // beam 90 at 0 deg: forward
  EXPECT_NEAR(std::atan2(g->directions[179].y(), g->directions[179].x()), 89.0 * kPi / 180, 1e-6);
  EXPECT_FLOAT_EQ(static_cast<float>(g->min_range), 0.1f);
  EXPECT_FLOAT_EQ(static_cast<float>(g->max_range), 81.8f);
  EXPECT_TRUE(g->mount.isApprox(Eigen::Isometry3d::Identity()));
}

TEST(MessageScanGeometry, OneObjectPerLayout) {
  MessageScanGeometry geometries;
  const msg::LaserScan a = scan_message(180, -1.5f, 0.01f);
  const auto first = geometries.for_message(a);
  EXPECT_EQ(geometries.for_message(a), first);
  const auto other = geometries.for_message(scan_message(361, -1.5f, 0.01f));
  EXPECT_NE(other, first);
  EXPECT_EQ(other->directions.size(), 361u);
}

TEST(MessageScanGeometry, TheScansOfALogRoundTrip) {
  Scan scan;
  auto geometry = std::make_shared<ScanGeometry>(ScanGeometry::planar(-kPi / 2, kPi / 360, 360));
  geometry->max_range = 81.0;
  scan.geometry = geometry;
  scan.ranges = std::vector<float>(360, 2.0f);
  const msg::LaserScan m = to_msg(scan, -kPi / 2, kPi / 360, Source{"laser", "uav1"});
  MessageScanGeometry geometries;
  const auto received = geometries.for_message(m);
  ASSERT_EQ(received->directions.size(), 360u);
  for (std::size_t i = 0; i < 360; i += 37) {
    EXPECT_NEAR((received->directions[i] - geometry->directions[i]).norm(), 0.0, 1e-6) << i;
  }
  EXPECT_FLOAT_EQ(static_cast<float>(received->max_range), 81.0f);
}

// A sensor file's scanner: its own geometry while the beam count matches; a real scanner's other
// layout (a UTM-30LX sends 1081 steps) keeps its beams, on the file's mount and mirror.
TEST(MessageScanGeometry, TheSensorsGeometryOrTheScansOwnLayoutOnTheSensorsMount) {
  LidarSpec lidar;  // 1080 beams over 270 deg
  lidar.mount_position = Vec3(0.1, 0.0, 0.2);
  lidar.floor_mirror.beams = 30;
  MessageScanGeometry geometries(lidar);
  ASSERT_TRUE(geometries.sensor_geometry());
  const auto configured = geometries.for_message(
      scan_message(1080, static_cast<float>(-0.75 * kPi), static_cast<float>(1.5 * kPi / 1079)));
  EXPECT_EQ(configured, geometries.sensor_geometry());
  EXPECT_FALSE(geometries.own_layout_used());

  const auto own = geometries.for_message(
      scan_message(1081, static_cast<float>(-0.75 * kPi), static_cast<float>(kPi / 720)));
  EXPECT_TRUE(geometries.own_layout_used());
  ASSERT_EQ(own->directions.size(), 1081u);
  EXPECT_TRUE(own->mount.translation().isApprox(Vec3(0.1, 0.0, 0.2)));
  EXPECT_LT(own->directions[0].z(), -0.9) << "the mirror's beams look down";
  EXPECT_EQ(own->directions[540].z(), 0.0);
}

// When each beam fired: a scan that says its time_increment (the simulator's, a SCIP 2.0
// driver's) gives its geometry fire times, taken over the sensor file's sweep; the file's sweep
// spreads over another layout's beams by angle; no word and no file's sweep: none.
TEST(MessageScanGeometry, TheBeamsFireWhenTheScanOrTheSensorFileSays) {
  LidarSpec lidar;  // 1080 beams over 270 deg
  lidar.sweep_seconds = 0.01875;
  Scan scan;
  scan.geometry = make_scan_geometry(lidar);
  scan.ranges = std::vector<float>(1080, 2.0f);
  const double increment = 1.5 * kPi / 1079;
  msg::LaserScan sent = to_msg(scan, -0.75 * kPi, increment, Source{"laser", "uav1"});
  EXPECT_FLOAT_EQ(sent.time_increment(), static_cast<float>(0.01875 / 1079));

  MessageScanGeometry plain;
  const auto received = plain.for_message(sent);
  ASSERT_EQ(received->fire_times.size(), 1080u);
  EXPECT_NEAR(received->fire_times.back(), 0.01875, 1e-7);
  EXPECT_EQ(plain.for_message(sent), received);
  sent.time_increment(0.0f);
  EXPECT_TRUE(plain.for_message(sent)->fire_times.empty());

  MessageScanGeometry from_file(lidar);
  EXPECT_NEAR(from_file.for_message(sent)->fire_times.back(), 0.01875, 1e-12);
  const auto other = from_file.for_message(
      scan_message(1081, static_cast<float>(-0.75 * kPi), static_cast<float>(kPi / 720)));
  ASSERT_EQ(other->fire_times.size(), 1081u);
  EXPECT_NEAR(other->fire_times.back(), 0.01875, 1e-8);  // 1080 steps of 0.25 degree
  sent.time_increment(1e-5f);
  EXPECT_NEAR(from_file.for_message(sent)->fire_times.back(), 1079 * 1e-5, 1e-9);
}

}  // namespace
}  // namespace uavslam::dds
