#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "SimTestHelpers.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam::sim {
namespace {

constexpr double kSampleStep = 0.1;            // s
constexpr double kMinFlightClearance = 0.5;    // m, everywhere along the flight
constexpr double kMinWaypointClearance = 0.8;  // m, at the waypoints

// Distance to the nearest surface other than the floor, which take-off and landing touch.
double clearance_above_floor(const World& world, const Vec3& p) {
  const Box& room = world.spec().room;
  const double walls = std::min({p.x() - room.min.x(), room.max.x() - p.x(), p.y() - room.min.y(),
                                 room.max.y() - p.y(), room.max.z() - p.z()});
  return std::min(walls, world.distance_to_nearest_obstacle(p));
}

class ShippedScenario : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedScenario, LoadsAndSimulates) {
  const Scenario scenario = testing::shipped_scenario(GetParam());
  EXPECT_EQ(scenario.name, GetParam());
  FlightSimulator simulator(scenario);
  Scan scan;
  ASSERT_TRUE(simulator.next_scan(scan));
  const auto valid = std::count_if(scan.ranges.begin(), scan.ranges.end(),
                                   [](float r) { return std::isfinite(r); });
  EXPECT_GT(valid, static_cast<long>(scan.ranges.size() / 2));
}

TEST_P(ShippedScenario, WaypointsKeepClearOfObstacles) {
  const Scenario scenario = testing::shipped_scenario(GetParam());
  const World world(scenario.world);
  for (const Waypoint& w : scenario.waypoints) {
    EXPECT_GE(world.distance_to_nearest_obstacle(w.position), kMinWaypointClearance)
        << "waypoint at t = " << w.t;
  }
}

TEST_P(ShippedScenario, FlightStaysClearOfEverySurfaceButTheFloor) {
  const Scenario scenario = testing::shipped_scenario(GetParam());
  const World world(scenario.world);
  const Trajectory trajectory(scenario.waypoints);
  const int samples =
      static_cast<int>((trajectory.end_time() - trajectory.start_time()) / kSampleStep);
  double tightest = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k) {
    const double t = trajectory.start_time() + k * kSampleStep;
    const Vec3 p = trajectory.pose_at(t).position;
    ASSERT_TRUE(world.is_free(p)) << "t = " << t;
    ASSERT_GT(p.z(), 0.1) << "t = " << t;
    const double clearance = clearance_above_floor(world, p);
    ASSERT_GE(clearance, kMinFlightClearance) << "t = " << t << " at " << p.transpose();
    tightest = std::min(tightest, clearance);
  }
  RecordProperty("tightest_clearance_m", std::to_string(tightest));
}

INSTANTIATE_TEST_SUITE_P(AllShipped, ShippedScenario,
                         ::testing::ValuesIn(testing::shipped_scenario_names()),
                         [](const auto& info) { return info.param; });

// config/scenarios/ground: ground robots for `simulate --carmen`, level, their scanner in its
// plane, clear of everything along the way (through 1 m doors; the splines' turns on the spot
// overshoot a little).
class GroundScenario : public ::testing::TestWithParam<std::string> {};

TEST_P(GroundScenario, IsALevelDriveClearOfTheWalls) {
  const Scenario ground = testing::shipped_scenario("ground/" + GetParam());
  EXPECT_EQ(ground.name, GetParam());
  EXPECT_EQ(ground.vehicle, Vehicle::ground);
  EXPECT_EQ(ground.lidar.rings, 1);
  EXPECT_EQ(ground.lidar.floor_mirror.beams, 0);
  const World world(ground.world);
  const Trajectory trajectory(ground.waypoints, ground.vehicle);
  double tightest = std::numeric_limits<double>::infinity();
  for (double t = trajectory.start_time(); t <= trajectory.end_time(); t += kSampleStep) {
    const Pose pose = trajectory.pose_at(t);
    ASSERT_TRUE(world.is_free(pose.position)) << "t = " << t;
    EXPECT_NEAR(pose.position.z(), 0.3, 1e-9) << "t = " << t;
    tightest = std::min(tightest, clearance_above_floor(world, pose.position));
  }
  EXPECT_GE(tightest, 0.4);
  RecordProperty("tightest_clearance_m", std::to_string(tightest));
}

INSTANTIATE_TEST_SUITE_P(Shipped, GroundScenario,
                         ::testing::Values("ring_corridor", "long_corridor", "offices",
                                           "round_hall", "pillar_hall", "large_ring", "busy_ring"),
                         [](const auto& info) { return info.param; });

TEST(DemoScenario, IsAThreeMinuteFlightAtWalkingPace) {
  const Scenario demo = testing::shipped_scenario("demo");
  const Trajectory trajectory(demo.waypoints);
  EXPECT_NEAR(trajectory.end_time() - trajectory.start_time(), 180.0, 10.0);
  double top_speed = 0.0, lowest = 10.0, highest = 0.0;
  for (double t = 10.0; t < 165.0; t += kSampleStep) {  // between take-off and landing
    top_speed = std::max(top_speed, trajectory.velocity_at(t).norm());
    lowest = std::min(lowest, trajectory.pose_at(t).position.z());
    highest = std::max(highest, trajectory.pose_at(t).position.z());
  }
  EXPECT_LE(top_speed, 1.3);
  EXPECT_GE(lowest, 0.9);
  EXPECT_LE(highest, 2.6);
  EXPECT_EQ(demo.lidar.beams, 1080);
  EXPECT_EQ(demo.lidar.floor_mirror.beams, 30);
  EXPECT_EQ(demo.seed, 1u);
}

class DriftingDemo : public ::testing::TestWithParam<std::string> {};

// yaw_drift.yaml and drift_change.yaml: the demo's room and flight, the IMU's heading drifting
// 2 degrees a minute (drift_change: until 90 s, 0.5 after).
TEST_P(DriftingDemo, IsTheDemoWithADriftingImu) {
  const Scenario demo = testing::shipped_scenario("demo");
  const Scenario drift = testing::shipped_scenario(GetParam());
  EXPECT_DOUBLE_EQ(drift.imu.yaw_drift_deg_per_min, 2.0);
  EXPECT_DOUBLE_EQ(demo.imu.yaw_drift_deg_per_min, 0.0);
  EXPECT_TRUE(demo.imu.yaw_drift_changes.empty());
  ASSERT_EQ(drift.waypoints.size(), demo.waypoints.size());
  for (std::size_t i = 0; i < demo.waypoints.size(); ++i) {
    EXPECT_EQ(drift.waypoints[i].t, demo.waypoints[i].t);
    EXPECT_EQ(drift.waypoints[i].position, demo.waypoints[i].position);
    EXPECT_EQ(drift.waypoints[i].yaw_deg, demo.waypoints[i].yaw_deg);
  }
  ASSERT_EQ(drift.world.boxes.size(), demo.world.boxes.size());
  for (std::size_t i = 0; i < demo.world.boxes.size(); ++i) {
    EXPECT_EQ(drift.world.boxes[i].min, demo.world.boxes[i].min);
    EXPECT_EQ(drift.world.boxes[i].max, demo.world.boxes[i].max);
  }
  EXPECT_EQ(drift.world.cylinders.size(), demo.world.cylinders.size());
}

INSTANTIATE_TEST_SUITE_P(Shipped, DriftingDemo, ::testing::Values("yaw_drift", "drift_change"),
                         [](const auto& info) { return info.param; });

// The corridor's flight, world and noise, with a real accelerometer's constant bias.
TEST(BiasedCorridorScenario, IsTheCorridorsFlightWithABiasedAccelerometer) {
  const Scenario corridor = testing::shipped_scenario("corridor");
  const Scenario biased = testing::shipped_scenario("biased_corridor");
  ASSERT_EQ(biased.waypoints.size(), corridor.waypoints.size());
  for (std::size_t i = 0; i < corridor.waypoints.size(); ++i) {
    EXPECT_EQ(biased.waypoints[i].position, corridor.waypoints[i].position);
  }
  EXPECT_EQ(biased.seed, corridor.seed);
  EXPECT_TRUE(corridor.imu.accel_bias.isZero());
  EXPECT_NEAR(biased.imu.accel_bias.norm(), 0.04, 0.01);  // 2-3 mg per axis
}

TEST(DriftChangeScenario, TheDriftSettlesAfterNinetySeconds) {
  const Scenario drift = testing::shipped_scenario("drift_change");
  ASSERT_EQ(drift.imu.yaw_drift_changes.size(), 1u);
  EXPECT_DOUBLE_EQ(drift.imu.yaw_drift_changes[0].t, 90.0);
  EXPECT_DOUBLE_EQ(drift.imu.yaw_drift_changes[0].deg_per_min, 0.5);
}

}  // namespace
}  // namespace uavslam::sim
