#include <cmath>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "TempDirTest.hpp"
#include "core/Angles.hpp"
#include "io/CarmenLog.hpp"
#include "io/CarmenWriter.hpp"
#include "io/RelationsFile.hpp"
#include "io/SimulatedCarmenLog.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam::io {
namespace {

using CarmenWriterTest = uavslam::test::TempDirTest;

TEST_F(CarmenWriterTest, WhatIsWrittenReadsBack) {
  CarmenScan scan;
  scan.message = CarmenScan::Message::robotlaser1;
  scan.ipc_timestamp = 12.5;
  scan.start_angle = -1.5;
  scan.angle_increment = 0.01;
  scan.max_range = 30.0;
  scan.ranges = {1.2345f, std::numeric_limits<float>::quiet_NaN(), 31.0f, 2.0f};
  scan.robot_pose = {1.0, 2.0, 0.5};
  scan.laser_pose = {1.1, 2.05, 0.5};
  CarmenOdometry odom;
  odom.pose = {1.0, 2.0, 0.5};
  odom.tv = 0.3;
  odom.rv = -0.1;
  odom.ipc_timestamp = 12.5;
  const std::string file = path("log.clf");
  write_carmen_log(file, {"a test log"}, {odom, scan});

  const CarmenLog log = read_carmen_log(file);
  EXPECT_EQ(log.malformed_lines, 0u);
  ASSERT_EQ(log.messages.size(), 2u);
  const auto& read_odom = std::get<CarmenOdometry>(log.messages[0]);
  EXPECT_DOUBLE_EQ(read_odom.pose.theta, 0.5);
  EXPECT_DOUBLE_EQ(read_odom.tv, 0.3);
  EXPECT_DOUBLE_EQ(read_odom.ipc_timestamp, 12.5);
  const auto& read = std::get<CarmenScan>(log.messages[1]);
  EXPECT_EQ(read.message, CarmenScan::Message::robotlaser1);
  EXPECT_DOUBLE_EQ(read.start_angle, -1.5);
  EXPECT_DOUBLE_EQ(read.angle_increment, 0.01);
  EXPECT_DOUBLE_EQ(read.max_range, 30.0);
  ASSERT_EQ(read.ranges.size(), 4u);
  EXPECT_FLOAT_EQ(read.ranges[0], 1.235f);  // to the millimetre (1.2345 in float is 1.23449...)
  EXPECT_FALSE(read.is_return(1));          // no return, written as the maximum range
  EXPECT_FALSE(read.is_return(2));
  EXPECT_TRUE(read.is_return(3));
  EXPECT_DOUBLE_EQ(read.laser_pose.x, 1.1);
  EXPECT_DOUBLE_EQ(read.robot_pose.y, 2.0);
  EXPECT_DOUBLE_EQ(read.ipc_timestamp, 12.5);
  const Eigen::Isometry3d mount = laser_mount(read);
  EXPECT_NEAR(mount.translation().x(), 0.1 * std::cos(0.5) + 0.05 * std::sin(0.5), 1e-3);
}

TEST_F(CarmenWriterTest, AnUnwritablePathIsNamed) {
  try {
    write_carmen_log("/nonexistent_dir/log.clf", {}, {});
    FAIL() << "expected a FileError";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("/nonexistent_dir/log.clf"));
  }
}

// A short ground run in an empty room: one ODOM and one ROBOTLASER1 per scan, the scanner's
// beams and mount as the scenario has them, the relations of its path.
TEST_F(CarmenWriterTest, ASimulatedGroundRunIsALogWithItsRelations) {
  sim::Scenario scenario;
  scenario.name = "room";
  scenario.world.room = {Vec3(0, 0, 0), Vec3(10, 8, 3)};
  scenario.vehicle = sim::Vehicle::ground;
  scenario.waypoints = {{0.0, Vec3(2, 2, 0.3), 0.0}, {20.0, Vec3(8, 6, 0.3), 60.0}};
  scenario.lidar.beams = 181;
  scenario.lidar.fov_deg = 180.0;
  scenario.lidar.rate_hz = 10.0;
  scenario.lidar.sweep_seconds = 0.0;
  scenario.lidar.mount_position = Vec3(0.1, 0.0, 0.3);
  sim::FlightSimulator simulator(scenario);
  std::vector<Scan> scans;
  std::vector<Pose> truth;
  for (Scan scan; simulator.next_scan(scan);) {
    truth.push_back(simulator.ground_truth_at(scan.stamp));
    scans.push_back(scan);
  }
  const std::string log_file = path("room.clf");
  const std::string relations_file = path("room.relations");
  const SimulatedCarmenFiles files =
      write_simulated_carmen_log(log_file, relations_file, scenario, scans, truth);
  EXPECT_EQ(files.scans, scans.size());
  EXPECT_NEAR(files.path_length, std::hypot(6.0, 4.0), 0.05);

  const CarmenLog log = read_carmen_log(log_file);
  EXPECT_EQ(log.malformed_lines, 0u);
  ASSERT_EQ(log.messages.size(), 2 * scans.size());
  const auto& first = std::get<CarmenScan>(log.messages[1]);
  EXPECT_NEAR(first.start_angle, -kPi / 2, 1e-6);
  EXPECT_NEAR(first.angle_increment, kPi / 180.0, 1e-6);
  EXPECT_EQ(first.ranges.size(), 181u);
  EXPECT_NEAR(laser_mount(first).translation().x(), 0.1, 1e-3);
  const std::vector<eval::Relation> relations = read_relations(relations_file);
  EXPECT_EQ(relations.size(), files.relations);
  EXPECT_GT(relations.size(), 20u);  // 7.2 m in steps of 0.2 m or 10 degrees

  // A tilted scanner is no planar log.
  scenario.lidar.mount_rpy_deg = Vec3(0.0, 10.0, 0.0);
  sim::FlightSimulator tilted(scenario);
  Scan scan;
  ASSERT_TRUE(tilted.next_scan(scan));
  EXPECT_THROW(write_simulated_carmen_log(log_file, relations_file, scenario, {scan},
                                          {tilted.ground_truth_at(scan.stamp)}),
               std::invalid_argument);
}

}  // namespace
}  // namespace uavslam::io
