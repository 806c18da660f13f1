#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/LaunchFile.hpp"
#include "io/ScenarioFile.hpp"
#include "io/SlamConfigFile.hpp"
#include "io/YamlReader.hpp"

namespace uavslam::io {
namespace {

using ::testing::HasSubstr;

const char* const kMinimalScenario = R"(
world:
  room: {min: [0, 0, 0], max: [10, 8, 3]}
trajectory:
  waypoints:
    - {t: 0, position: [1, 1, 1]}
    - {t: 5, position: [2, 1, 1], yaw_deg: 90}
)";

// Writes YAML files under the test temp dir and removes them at the end of each test.
class YamlFileTest : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = ::testing::TempDir() + "uavslam_yaml_" + name;
    std::ofstream(path) << text;
    written_.push_back(path);
    return path;
  }

  // The scenario with `from` replaced by `to` (which must occur in it).
  std::string minimal_scenario_with(const std::string& from, const std::string& to) {
    std::string text = kMinimalScenario;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  }

  void TearDown() override {
    for (const std::string& path : written_) std::remove(path.c_str());
  }

 private:
  std::vector<std::string> written_;
};

// Runs `load`, which must throw ConfigError, and returns the message.
std::string config_error_of(const std::function<void()>& load) {
  try {
    load();
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ConfigError thrown";
  return "";
}

TEST_F(YamlFileTest, MinimalScenarioTakesTheDefaults) {
  const std::string path = write("minimal.yaml", kMinimalScenario);
  const sim::Scenario scenario = load_scenario(path);
  EXPECT_EQ(scenario.name, "uavslam_yaml_minimal");  // the file's stem
  EXPECT_EQ(scenario.world.room.max, Vec3(10.0, 8.0, 3.0));
  ASSERT_EQ(scenario.waypoints.size(), 2u);
  EXPECT_EQ(scenario.waypoints[0].yaw_deg, 0.0);
  EXPECT_EQ(scenario.waypoints[1].yaw_deg, 90.0);
  EXPECT_EQ(scenario.waypoints[1].position, Vec3(2.0, 1.0, 1.0));
  const LidarSpec lidar_defaults;
  EXPECT_EQ(scenario.lidar.beams, lidar_defaults.beams);
  EXPECT_EQ(scenario.lidar.mount_position, lidar_defaults.mount_position);
  EXPECT_EQ(scenario.imu.rate_hz, sim::ImuSpec{}.rate_hz);
  EXPECT_EQ(scenario.seed, 1u);
  EXPECT_TRUE(scenario.world.boxes.empty());
}

TEST_F(YamlFileTest, FullScenarioReadsEveryKey) {
  const std::string path = write("full.yaml", std::string(R"(
name: full
seed: 42
world:
  room: {min: [0, 0, 0], max: [10, 8, 3]}
  boxes:
    - {min: [5, 5, 0], max: [6, 6, 1]}
  cylinders:
    - {center: [8, 2], radius: 0.3, z: [0, 2.5]}
  arcs:
    - {center: [5, 4], radius: 2, from_deg: -90, to_deg: 180, z: [0, 2]}
  people:
    - {path: [[1, 7], [9, 7], [9, 2]], speed: 1.5, start: 2, radius: 0.3, height: 1.7}
trajectory:
  vehicle: ground
  waypoints:
    - {t: 1, position: [1, 1, 1], yaw_deg: 10}
    - {t: 3, position: [2, 1, 1], yaw_deg: 20}
lidar:
  beams: 720
  fov_deg: 240
  rate_hz: 20
  min_range: 0.2
  max_range: 25
  range_noise_std: 0.02
  sweep_seconds: 0.04
  mount: {position: [0.1, 0, 0.2], rpy_deg: [0, 0, 180]}
  floor_mirror: {beams: 12, spread_deg: 15}
  rings: 4
  vertical_fov_deg: 20
imu:
  rate_hz: 100
  orientation_noise_std_deg: 0.2
  yaw_drift_deg_per_min: -1.5
  gyro_noise_std: 0.002
  accel_noise_std: 0.05
  accel_bias: [0.01, -0.02, 0.03]
velocity: {rate_hz: 25, noise_std: 0.08}
faults: {late_scan_every: 20, late_scan_s: 0.15}
odometry:
  translation_scale_error: -0.02
  turn_scale_error: 0.03
  translation_noise: 0.04
  turn_noise: 0.05
  turn_per_metre_noise: 0.06
)"));
  const sim::Scenario s = load_scenario(path);
  EXPECT_EQ(s.name, "full");
  EXPECT_EQ(s.seed, 42u);
  ASSERT_EQ(s.world.boxes.size(), 1u);
  EXPECT_EQ(s.world.boxes[0].min, Vec3(5.0, 5.0, 0.0));
  ASSERT_EQ(s.world.cylinders.size(), 1u);
  EXPECT_EQ(s.world.cylinders[0].center, Eigen::Vector2d(8.0, 2.0));
  EXPECT_EQ(s.world.cylinders[0].radius, 0.3);
  EXPECT_EQ(s.world.cylinders[0].z1, 2.5);
  ASSERT_EQ(s.world.arcs.size(), 1u);
  EXPECT_EQ(s.world.arcs[0].center, Eigen::Vector2d(5.0, 4.0));
  EXPECT_EQ(s.world.arcs[0].radius, 2.0);
  EXPECT_EQ(s.world.arcs[0].from_deg, -90.0);
  EXPECT_EQ(s.world.arcs[0].to_deg, 180.0);
  EXPECT_EQ(s.world.arcs[0].z1, 2.0);
  ASSERT_EQ(s.world.people.size(), 1u);
  ASSERT_EQ(s.world.people[0].path.size(), 3u);
  EXPECT_EQ(s.world.people[0].path[2], Eigen::Vector2d(9.0, 2.0));
  EXPECT_EQ(s.world.people[0].speed, 1.5);
  EXPECT_EQ(s.world.people[0].start, 2.0);
  EXPECT_EQ(s.world.people[0].radius, 0.3);
  EXPECT_EQ(s.world.people[0].height, 1.7);
  EXPECT_EQ(s.waypoints[0].t, 1.0);
  EXPECT_EQ(s.lidar.beams, 720);
  EXPECT_EQ(s.lidar.fov_deg, 240.0);
  EXPECT_EQ(s.lidar.rate_hz, 20.0);
  EXPECT_EQ(s.lidar.min_range, 0.2);
  EXPECT_EQ(s.lidar.max_range, 25.0);
  EXPECT_EQ(s.lidar.range_noise_std, 0.02);
  EXPECT_EQ(s.lidar.sweep_seconds, 0.04);
  EXPECT_EQ(s.lidar.mount_position, Vec3(0.1, 0.0, 0.2));
  EXPECT_EQ(s.lidar.mount_rpy_deg, Vec3(0.0, 0.0, 180.0));
  EXPECT_EQ(s.lidar.floor_mirror.beams, 12);
  EXPECT_EQ(s.lidar.floor_mirror.spread_deg, 15.0);
  EXPECT_EQ(s.lidar.rings, 4);
  EXPECT_EQ(s.lidar.vertical_fov_deg, 20.0);
  EXPECT_EQ(s.imu.rate_hz, 100.0);
  EXPECT_EQ(s.imu.orientation_noise_std_deg, 0.2);
  EXPECT_EQ(s.imu.yaw_drift_deg_per_min, -1.5);
  EXPECT_EQ(s.imu.gyro_noise_std, 0.002);
  EXPECT_EQ(s.imu.accel_noise_std, 0.05);
  EXPECT_EQ(s.imu.accel_bias, Vec3(0.01, -0.02, 0.03));
  EXPECT_EQ(s.velocity.rate_hz, 25.0);
  EXPECT_EQ(s.velocity.noise_std, 0.08);
  EXPECT_EQ(s.faults.late_scan_every, 20);
  EXPECT_EQ(s.faults.late_scan_s, 0.15);
  EXPECT_EQ(s.vehicle, sim::Vehicle::ground);
  EXPECT_EQ(s.odometry.translation_scale_error, -0.02);
  EXPECT_EQ(s.odometry.turn_scale_error, 0.03);
  EXPECT_EQ(s.odometry.translation_noise, 0.04);
  EXPECT_EQ(s.odometry.turn_noise, 0.05);
  EXPECT_EQ(s.odometry.turn_per_metre_noise, 0.06);
  // Without the section the vehicle has no velocity source; without `vehicle`, it flies.
  const sim::Scenario plain = load_scenario(write("plain.yaml", kMinimalScenario));
  EXPECT_EQ(plain.velocity.rate_hz, 0.0);
  EXPECT_EQ(plain.vehicle, sim::Vehicle::multirotor);
}

TEST_F(YamlFileTest, AVehicleIsAMultirotorOrAGroundRobot) {
  const std::string path =
      write("boat.yaml", minimal_scenario_with("  waypoints:", "  vehicle: boat\n  waypoints:"));
  EXPECT_THAT(
      config_error_of([&] { load_scenario(path); }),
      ::testing::AllOf(::testing::HasSubstr("vehicle"),
                       ::testing::HasSubstr("multirotor or ground"), ::testing::HasSubstr("boat")));
}

TEST_F(YamlFileTest, MissingRequiredKeyIsNamed) {
  const std::string path =
      write("no_room.yaml", minimal_scenario_with("room: {min: [0, 0, 0], max: [10, 8, 3]}", "{}"));
  const std::string message = config_error_of([&] { load_scenario(path); });
  EXPECT_THAT(message, HasSubstr(path + ": missing required key 'world.room'"));
}

// The matcher's --sensor: a file of a real scanner alone, or a whole scenario.
TEST_F(YamlFileTest, ASensorFileHoldsOnlyTheScanner) {
  const SensorFile shipped =
      load_sensor(std::string(UAVSLAM_SOURCE_DIR) + "/config/sensors/hokuyo_utm30lx.yaml");
  EXPECT_EQ(shipped.sensor.name, "hokuyo_utm30lx");
  EXPECT_EQ(shipped.sensor.lidar.beams, 1081);
  EXPECT_EQ(shipped.sensor.lidar.floor_mirror.beams, 30);
  EXPECT_FALSE(shipped.take_off);

  const SensorFile scenario = load_sensor(write("scenario.yaml", kMinimalScenario));
  const sim::Scenario flight_of = load_scenario(write("again.yaml", kMinimalScenario));
  ASSERT_TRUE(scenario.take_off);
  EXPECT_EQ(*scenario.take_off, flight_of.waypoints.front().position);
  EXPECT_EQ(scenario.sensor.lidar.beams, flight_of.lidar.beams);

  const std::string no_lidar = write("no_lidar.yaml", "name: bare\n");
  EXPECT_THAT(config_error_of([&] { load_sensor(no_lidar); }),
              HasSubstr(no_lidar + ": missing required key 'lidar'"));
  const std::string flight = write("flight.yaml", "lidar: {beams: 10}\ntrajectory: {}\n");
  EXPECT_THAT(config_error_of([&] { load_sensor(flight); }), HasSubstr("trajectory"));
}

TEST_F(YamlFileTest, IllTypedValueNamesFileKeyAndValue) {
  const std::string path =
      write("fast.yaml", std::string(kMinimalScenario) + "lidar:\n  rate_hz: fast\n");
  const std::string message = config_error_of([&] { load_scenario(path); });
  EXPECT_THAT(message,
              HasSubstr(path + ": key 'lidar.rate_hz': expected a number > 0, got 'fast'"));
  EXPECT_THAT(message, HasSubstr("line 9"));
}

TEST_F(YamlFileTest, BadListElementIsNamedByIndex) {
  const std::string path =
      write("rpy.yaml", std::string(kMinimalScenario) + "lidar:\n  mount: {rpy_deg: [0, 0, up]}\n");
  EXPECT_THAT(config_error_of([&] { load_scenario(path); }),
              HasSubstr("key 'lidar.mount.rpy_deg[2]': expected a number, got 'up'"));
}

TEST_F(YamlFileTest, WrongLengthVectorIsRejected) {
  const std::string path =
      write("short_vec.yaml", minimal_scenario_with("position: [1, 1, 1]", "position: [1, 1]"));
  EXPECT_THAT(config_error_of([&] { load_scenario(path); }),
              HasSubstr("key 'trajectory.waypoints[0].position': expected a list of 3 numbers "
                        "[x, y, z], got '[1, 1]'"));
}

TEST_F(YamlFileTest, UnknownKeyIsAnError) {
  const std::string path =
      write("typo.yaml", std::string(kMinimalScenario) + "lidar:\n  rat_hz: 40\n");
  const std::string message = config_error_of([&] { load_scenario(path); });
  EXPECT_THAT(message, HasSubstr(path + ": unknown key 'lidar.rat_hz'"));
  EXPECT_THAT(message, HasSubstr("rate_hz"));  // the allowed keys are listed
}

TEST_F(YamlFileTest, FractionalIntegerIsRejected) {
  const std::string path =
      write("beams.yaml", std::string(kMinimalScenario) + "lidar:\n  beams: 2.5\n");
  EXPECT_THAT(config_error_of([&] { load_scenario(path); }),
              HasSubstr("key 'lidar.beams': expected an integer >= 1, got '2.5'"));
}

TEST_F(YamlFileTest, OutOfRangeValueIsRejected) {
  const std::string path =
      write("rate.yaml", std::string(kMinimalScenario) + "imu:\n  rate_hz: -5\n");
  EXPECT_THAT(config_error_of([&] { load_scenario(path); }),
              HasSubstr("key 'imu.rate_hz': expected a number > 0, got '-5'"));
}

// A sweep cannot outlast the scan period it belongs to.
TEST_F(YamlFileTest, ASweepLongerThanTheScanPeriodIsRejected) {
  const std::string path =
      write("sweep.yaml",
            std::string(kMinimalScenario) + "lidar:\n  rate_hz: 40\n  sweep_seconds: 0.03\n");
  EXPECT_THAT(config_error_of([&] { load_scenario(path); }),
              HasSubstr("key 'lidar.sweep_seconds'"));
}

// The heading drift's changes: read in time order, one out of order named with its index.
TEST_F(YamlFileTest, DriftChangesComeInTimeOrder) {
  const std::string good =
      write("changes.yaml", std::string(kMinimalScenario) +
                                "imu:\n  yaw_drift_changes:\n    - {t: 10, deg_per_min: 1}\n"
                                "    - {t: 20, deg_per_min: -0.5}\n");
  const sim::Scenario s = load_scenario(good);
  ASSERT_EQ(s.imu.yaw_drift_changes.size(), 2u);
  EXPECT_EQ(s.imu.yaw_drift_changes[1].t, 20.0);
  EXPECT_EQ(s.imu.yaw_drift_changes[1].deg_per_min, -0.5);
  const std::string bad =
      write("order.yaml", std::string(kMinimalScenario) +
                              "imu:\n  yaw_drift_changes:\n    - {t: 20, deg_per_min: 1}\n"
                              "    - {t: 10, deg_per_min: -0.5}\n");
  EXPECT_THAT(config_error_of([&] { load_scenario(bad); }),
              HasSubstr("key 'imu.yaw_drift_changes[1].t': expected a number > 20, got '10'"));
}

TEST_F(YamlFileTest, MirrorCannotTakeMoreBeamsThanTheScanner) {
  const std::string path = write("mirror.yaml", std::string(kMinimalScenario) +
                                                    "lidar:\n  beams: 10\n  floor_mirror: "
                                                    "{beams: 11}\n");
  EXPECT_THAT(
      config_error_of([&] { load_scenario(path); }),
      HasSubstr("key 'lidar.floor_mirror.beams': expected an integer in [0, 10], got '11'"));
}

TEST_F(YamlFileTest, RoomMustHaveMinBelowMax) {
  const std::string path =
      write("room.yaml", minimal_scenario_with("max: [10, 8, 3]", "max: [10, 8, -3]"));
  EXPECT_THAT(config_error_of([&] { load_scenario(path); }),
              HasSubstr("key 'world.room': expected min < max on every axis"));
}

TEST_F(YamlFileTest, AWalkersPathHasTwoPointsAtLeast) {
  const std::string path =
      write("walker.yaml", minimal_scenario_with("max: [10, 8, 3]}",
                                                 "max: [10, 8, 3]}\n  people:\n"
                                                 "    - {path: [[1, 1]]}"));
  EXPECT_THAT(
      config_error_of([&] { load_scenario(path); }),
      HasSubstr("key 'world.people[0].path': expected a path of two points [x, y] at least"));
}

TEST_F(YamlFileTest, WaypointTimesMustIncrease) {
  const std::string path = write("times.yaml", minimal_scenario_with("t: 5", "t: 0"));
  EXPECT_THAT(config_error_of([&] { load_scenario(path); }),
              HasSubstr("key 'trajectory.waypoints[1].t': expected a time after the previous "
                        "waypoint's 0, got '0'"));
}

TEST_F(YamlFileTest, WaypointsMustBeInsideTheRoom) {
  const std::string path =
      write("outside.yaml", minimal_scenario_with("position: [2, 1, 1]", "position: [12, 1, 1]"));
  EXPECT_THAT(config_error_of([&] { load_scenario(path); }),
              HasSubstr("key 'trajectory.waypoints[1].position': expected a point inside the "
                        "room and outside every obstacle, got '[12, 1, 1]'"));
}

TEST_F(YamlFileTest, AtLeastTwoWaypoints) {
  const std::string path = write(
      "one.yaml", minimal_scenario_with("    - {t: 5, position: [2, 1, 1], yaw_deg: 90}\n", ""));
  EXPECT_THAT(config_error_of([&] { load_scenario(path); }),
              HasSubstr("key 'trajectory.waypoints': expected a list of at least 2 waypoints"));
}

TEST_F(YamlFileTest, MissingFileIsNamed) {
  const std::string path = ::testing::TempDir() + "uavslam_yaml_does_not_exist.yaml";
  const std::string message = config_error_of([&] { load_scenario(path); });
  EXPECT_THAT(message, HasSubstr("cannot read scenario file '" + path + "'"));
  EXPECT_THAT(message, HasSubstr("No such file"));
}

TEST_F(YamlFileTest, MalformedYamlGivesTheLine) {
  const std::string path = write("broken.yaml", "world:\n  room: {min: [0, 0, 0]\n");
  const std::string message = config_error_of([&] { load_scenario(path); });
  EXPECT_THAT(message, HasSubstr("cannot read scenario file '" + path + "': line "));
  EXPECT_THAT(message, HasSubstr("column"));
}

TEST_F(YamlFileTest, ConfigErrorIsARuntimeError) {
  EXPECT_THROW(load_slam_config(::testing::TempDir() + "uavslam_yaml_missing.yaml"),
               std::runtime_error);
}

void expect_default_slam_config(const SlamConfig& config) {
  const SlamConfig defaults;
  EXPECT_EQ(config.scan.subsample_every, defaults.scan.subsample_every);
  EXPECT_EQ(config.scan.floor_margin, defaults.scan.floor_margin);
  EXPECT_EQ(config.scan.deskew, defaults.scan.deskew);
  EXPECT_EQ(config.icp.iterations, defaults.icp.iterations);
  EXPECT_EQ(config.icp.max_translation, defaults.icp.max_translation);
  EXPECT_EQ(config.icp.motion_prior, defaults.icp.motion_prior);
  EXPECT_EQ(config.icp.max_error_after, defaults.icp.max_error_after);
  EXPECT_EQ(config.icp.max_error_ratio, defaults.icp.max_error_ratio);
  EXPECT_EQ(config.icp.max_correspondence_distance, defaults.icp.max_correspondence_distance);
  EXPECT_EQ(config.icp.heading, defaults.icp.heading);
  EXPECT_EQ(config.icp.heading_check_every, defaults.icp.heading_check_every);
  EXPECT_EQ(config.icp.heading_check_tolerance, defaults.icp.heading_check_tolerance);
  EXPECT_EQ(config.icp.heading_anchor, defaults.icp.heading_anchor);
  EXPECT_EQ(config.icp.heading_max_tilt, defaults.icp.heading_max_tilt);
  EXPECT_EQ(config.icp.max_rotation, defaults.icp.max_rotation);
  EXPECT_EQ(config.icp.metric, defaults.icp.metric);
  EXPECT_EQ(config.icp.prior_weight, defaults.icp.prior_weight);
  EXPECT_EQ(config.icp.robust_scale, defaults.icp.robust_scale);
  EXPECT_EQ(config.icp.refine_iterations, defaults.icp.refine_iterations);
  EXPECT_EQ(config.icp.stop_step, defaults.icp.stop_step);
  EXPECT_EQ(config.map.keyframe_rotation, defaults.map.keyframe_rotation);
  EXPECT_EQ(config.map.min_point_spacing, defaults.map.min_point_spacing);
  EXPECT_EQ(config.nearest_neighbour.index, defaults.nearest_neighbour.index);
  EXPECT_EQ(config.nearest_neighbour.flann_trees, defaults.nearest_neighbour.flann_trees);
  EXPECT_EQ(config.nearest_neighbour.flann_checks, defaults.nearest_neighbour.flann_checks);
  EXPECT_EQ(config.map.keyframe_height, defaults.map.keyframe_height);
  EXPECT_EQ(config.map.keyframe_lateral, defaults.map.keyframe_lateral);
  EXPECT_EQ(config.imu.max_gap, defaults.imu.max_gap);
  EXPECT_EQ(config.imu.attitude_sigma, defaults.imu.attitude_sigma);
  EXPECT_EQ(config.imu.heading_sigma, defaults.imu.heading_sigma);
  EXPECT_EQ(config.icp.prior_gate, defaults.icp.prior_gate);
  EXPECT_EQ(config.icp.prior_gate_overrule, defaults.icp.prior_gate_overrule);
  EXPECT_EQ(config.degeneracy.threshold, defaults.degeneracy.threshold);
  EXPECT_EQ(config.degeneracy.min_sigma, defaults.degeneracy.min_sigma);
  EXPECT_EQ(config.motion.accel_noise_density, defaults.motion.accel_noise_density);
  EXPECT_EQ(config.motion.accel_bias_walk, defaults.motion.accel_bias_walk);
  EXPECT_EQ(config.motion.initial_speed_sigma, defaults.motion.initial_speed_sigma);
  EXPECT_EQ(config.motion.initial_bias_sigma, defaults.motion.initial_bias_sigma);
  EXPECT_EQ(config.motion.match_error_sigma, defaults.motion.match_error_sigma);
  EXPECT_EQ(config.motion.match_error_distance, defaults.motion.match_error_distance);
  EXPECT_EQ(config.motion.odometry_noise_per_metre, defaults.motion.odometry_noise_per_metre);
  EXPECT_EQ(config.motion.odometry_noise_floor, defaults.motion.odometry_noise_floor);
  EXPECT_EQ(config.motion.fuse_velocity, defaults.motion.fuse_velocity);
  EXPECT_EQ(config.loop_closure.enabled, defaults.loop_closure.enabled);
  EXPECT_EQ(config.loop_closure.step_sigma, defaults.loop_closure.step_sigma);
  EXPECT_EQ(config.loop_closure.step_sigma_per_metre, defaults.loop_closure.step_sigma_per_metre);
  EXPECT_EQ(config.loop_closure.step_yaw_sigma, defaults.loop_closure.step_yaw_sigma);
  EXPECT_EQ(config.loop_closure.step_yaw_sigma_per_radian,
            defaults.loop_closure.step_yaw_sigma_per_radian);
  EXPECT_EQ(config.loop_closure.loop_sigma, defaults.loop_closure.loop_sigma);
  EXPECT_EQ(config.loop_closure.loop_yaw_sigma, defaults.loop_closure.loop_yaw_sigma);
  EXPECT_EQ(config.loop_closure.min_travel, defaults.loop_closure.min_travel);
  EXPECT_EQ(config.loop_closure.min_radius, defaults.loop_closure.min_radius);
  EXPECT_EQ(config.loop_closure.max_radius, defaults.loop_closure.max_radius);
  EXPECT_EQ(config.loop_closure.known_radius, defaults.loop_closure.known_radius);
  EXPECT_EQ(config.loop_closure.max_candidates, defaults.loop_closure.max_candidates);
  EXPECT_EQ(config.loop_closure.submap_keyframes, defaults.loop_closure.submap_keyframes);
  EXPECT_EQ(config.loop_closure.resolution, defaults.loop_closure.resolution);
  EXPECT_EQ(config.loop_closure.min_score, defaults.loop_closure.min_score);
  EXPECT_EQ(config.loop_closure.min_score_margin, defaults.loop_closure.min_score_margin);
  EXPECT_EQ(config.loop_closure.ambiguity_radius, defaults.loop_closure.ambiguity_radius);
}

TEST(SlamConfigFile, TheSeedsConfigHoldsTheDefaults) {
  expect_default_slam_config(
      load_slam_config(std::string(UAVSLAM_SOURCE_DIR) + "/config/seed.yaml"));
}

// The UAV's configuration is the seed's plus the motion model, the degeneracy analysis, the
// seed's own suggestion of a periodic heading check, the gate on the motion prior, the robust
// refinement, the floor strikes set aside, the sweep's motion undone, the matches' shared error
// and the back end.
TEST(SlamConfigFile,
     TheUavsConfigIsTheSeedWithTheMotionPriorsDegeneracyAnchoredHeadingGateAndLines) {
  SlamConfig config = load_slam_config(std::string(UAVSLAM_SOURCE_DIR) + "/config/slam.yaml");
  EXPECT_EQ(config.icp.motion_prior, MotionPrior::Imu);
  EXPECT_EQ(config.icp.metric, IcpMetric::PointToLine);
  EXPECT_GT(config.degeneracy.threshold, 0.0);
  EXPECT_EQ(config.icp.heading, HeadingMode::EveryScan);
  EXPECT_GT(config.icp.heading_anchor, 0.0);
  EXPECT_GT(config.icp.heading_max_tilt, 0.0);
  EXPECT_GT(config.icp.prior_gate, 0.0);
  EXPECT_TRUE(config.motion.fuse_velocity);
  EXPECT_GT(config.motion.match_error_sigma, 0.0);
  EXPECT_TRUE(config.loop_closure.enabled);
  EXPECT_GT(config.icp.robust_scale, 0.0);
  EXPECT_GT(config.scan.floor_margin, 0.0);
  EXPECT_TRUE(config.scan.deskew);
  config.icp.robust_scale = SlamConfig{}.icp.robust_scale;
  config.scan.floor_margin = SlamConfig{}.scan.floor_margin;
  config.scan.deskew = SlamConfig{}.scan.deskew;
  config.loop_closure.enabled = SlamConfig{}.loop_closure.enabled;
  config.icp.motion_prior = SlamConfig{}.icp.motion_prior;
  config.motion.fuse_velocity = SlamConfig{}.motion.fuse_velocity;
  config.motion.match_error_sigma = SlamConfig{}.motion.match_error_sigma;
  config.degeneracy.threshold = SlamConfig{}.degeneracy.threshold;
  config.icp.heading = SlamConfig{}.icp.heading;
  config.icp.heading_anchor = SlamConfig{}.icp.heading_anchor;
  config.icp.heading_max_tilt = SlamConfig{}.icp.heading_max_tilt;
  config.icp.prior_gate = SlamConfig{}.icp.prior_gate;
  config.icp.metric = SlamConfig{}.icp.metric;
  expect_default_slam_config(config);
}

TEST_F(YamlFileTest, EmptySlamConfigHoldsTheDefaults) {
  expect_default_slam_config(load_slam_config(write("empty.yaml", "# nothing set\n")));
}

TEST_F(YamlFileTest, SlamConfigReadsEveryKey) {
  const std::string path = write("slam.yaml", R"(
scan: {subsample_every: 1, floor_margin: 0.15, deskew: true}
icp:
  iterations: 20
  max_translation: 0.5
  max_error_after: 0.1
  max_error_ratio: 0.9
  max_correspondence_distance: 1.5
  motion_prior: odometry
  heading: periodic_check
  heading_check_every: 7
  heading_check_tolerance: 0.02
  heading_anchor: 2.5
  heading_max_tilt: 0.3
  max_rotation: 0.2
  metric: point_to_line
  prior_weight: 0.01
  robust_scale: 0.05
  refine_iterations: 3
  stop_step: 0.001
  prior_gate: 4
  prior_gate_overrule: 7
nearest_neighbour: {index: exact, flann_trees: 8, flann_checks: 128}
map: {keyframe_height: 0.1, keyframe_lateral: 0.25, keyframe_rotation: 0.3, min_point_spacing: 0.03}
imu: {max_gap: 0.02, attitude_sigma: 0.01, heading_sigma: 0.05}
degeneracy: {threshold: 0.04, min_sigma: 0.02, hold_blind_yaw: false}
free_space: {enabled: true, resolution: 0.2, reach: 7, min_passes: 3, memory: 4}
motion:
  accel_noise_density: 0.01
  accel_bias_walk: 0.001
  initial_speed_sigma: 0.5
  initial_bias_sigma: 0.2
  match_error_sigma: 0.004
  match_error_distance: 0.7
  odometry_noise_per_metre: 0.05
  odometry_noise_floor: 0.003
  fuse_velocity: true
loop_closure:
  enabled: true
  step_sigma: 0.02
  step_sigma_per_metre: 0.03
  step_yaw_sigma: 0.004
  step_yaw_sigma_per_radian: 0.05
  loop_sigma: 0.1
  loop_yaw_sigma: 0.03
  min_travel: 5
  min_radius: 0.5
  max_radius: 4
  known_radius: 0.3
  max_candidates: 3
  submap_keyframes: 2
  resolution: 0.1
  min_score: 0.6
  min_score_margin: 0.1
  ambiguity_radius: 0.7
  max_opposed_share: 0.4
)");
  const SlamConfig c = load_slam_config(path);
  EXPECT_EQ(c.degeneracy.threshold, 0.04);
  EXPECT_EQ(c.degeneracy.min_sigma, 0.02);
  EXPECT_FALSE(c.degeneracy.hold_blind_yaw);
  EXPECT_TRUE(SlamConfig{}.degeneracy.hold_blind_yaw);
  EXPECT_TRUE(c.free_space.enabled);
  EXPECT_FALSE(SlamConfig{}.free_space.enabled);
  EXPECT_EQ(c.free_space.resolution, 0.2);
  EXPECT_EQ(c.free_space.reach, 7.0);
  EXPECT_EQ(c.free_space.min_passes, 3);
  EXPECT_EQ(c.free_space.memory, 4.0);
  EXPECT_EQ(c.motion.accel_noise_density, 0.01);
  EXPECT_EQ(c.motion.accel_bias_walk, 0.001);
  EXPECT_EQ(c.motion.initial_speed_sigma, 0.5);
  EXPECT_EQ(c.motion.initial_bias_sigma, 0.2);
  EXPECT_EQ(c.motion.match_error_sigma, 0.004);
  EXPECT_EQ(c.motion.match_error_distance, 0.7);
  EXPECT_EQ(c.motion.odometry_noise_per_metre, 0.05);
  EXPECT_EQ(c.motion.odometry_noise_floor, 0.003);
  EXPECT_TRUE(c.motion.fuse_velocity);
  EXPECT_TRUE(c.loop_closure.enabled);
  EXPECT_EQ(c.loop_closure.step_sigma, 0.02);
  EXPECT_EQ(c.loop_closure.step_sigma_per_metre, 0.03);
  EXPECT_EQ(c.loop_closure.step_yaw_sigma, 0.004);
  EXPECT_EQ(c.loop_closure.step_yaw_sigma_per_radian, 0.05);
  EXPECT_EQ(c.loop_closure.loop_sigma, 0.1);
  EXPECT_EQ(c.loop_closure.loop_yaw_sigma, 0.03);
  EXPECT_EQ(c.loop_closure.min_travel, 5.0);
  EXPECT_EQ(c.loop_closure.min_radius, 0.5);
  EXPECT_EQ(c.loop_closure.max_radius, 4.0);
  EXPECT_EQ(c.loop_closure.known_radius, 0.3);
  EXPECT_EQ(c.loop_closure.max_candidates, 3);
  EXPECT_EQ(c.loop_closure.submap_keyframes, 2);
  EXPECT_EQ(c.loop_closure.resolution, 0.1);
  EXPECT_EQ(c.loop_closure.min_score, 0.6);
  EXPECT_EQ(c.loop_closure.min_score_margin, 0.1);
  EXPECT_EQ(c.loop_closure.ambiguity_radius, 0.7);
  EXPECT_EQ(c.loop_closure.max_opposed_share, 0.4);
  EXPECT_EQ(c.scan.subsample_every, 1);
  EXPECT_EQ(c.scan.floor_margin, 0.15);
  EXPECT_TRUE(c.scan.deskew);
  EXPECT_EQ(c.icp.iterations, 20);
  EXPECT_EQ(c.icp.max_translation, 0.5);
  EXPECT_EQ(c.icp.max_error_after, 0.1);
  EXPECT_EQ(c.icp.max_error_ratio, 0.9);
  EXPECT_EQ(c.icp.max_correspondence_distance, 1.5);
  EXPECT_EQ(c.icp.motion_prior, MotionPrior::Odometry);
  EXPECT_EQ(c.icp.heading, HeadingMode::PeriodicCheck);
  EXPECT_EQ(c.icp.heading_check_every, 7);
  EXPECT_EQ(c.icp.heading_check_tolerance, 0.02);
  EXPECT_EQ(c.icp.heading_anchor, 2.5);
  EXPECT_EQ(c.icp.heading_max_tilt, 0.3);
  EXPECT_EQ(c.icp.max_rotation, 0.2);
  EXPECT_EQ(c.icp.metric, IcpMetric::PointToLine);
  EXPECT_EQ(c.icp.prior_weight, 0.01);
  EXPECT_EQ(c.icp.robust_scale, 0.05);
  EXPECT_EQ(c.icp.refine_iterations, 3);
  EXPECT_EQ(c.icp.stop_step, 0.001);
  EXPECT_EQ(c.icp.prior_gate, 4.0);
  EXPECT_EQ(c.icp.prior_gate_overrule, 7);
  EXPECT_EQ(c.map.keyframe_rotation, 0.3);
  EXPECT_EQ(c.map.min_point_spacing, 0.03);
  EXPECT_EQ(c.nearest_neighbour.index, IndexKind::Exact);
  EXPECT_EQ(c.nearest_neighbour.flann_trees, 8);
  EXPECT_EQ(c.nearest_neighbour.flann_checks, 128);
  EXPECT_EQ(c.map.keyframe_height, 0.1);
  EXPECT_EQ(c.map.keyframe_lateral, 0.25);
  EXPECT_EQ(c.imu.max_gap, 0.02);
  EXPECT_EQ(c.imu.attitude_sigma, 0.01);
  EXPECT_EQ(c.imu.heading_sigma, 0.05);
}

TEST_F(YamlFileTest, SlamConfigRejectsAnUnknownIndex) {
  const std::string path = write("index.yaml", "nearest_neighbour:\n  index: kdtree\n");
  EXPECT_THAT(config_error_of([&] { load_slam_config(path); }),
              HasSubstr(path + ": key 'nearest_neighbour.index': expected one of 'flann', "
                               "'exact', 'brute', got 'kdtree'"));
}

TEST_F(YamlFileTest, SlamConfigRejectsATypo) {
  const std::string path = write("iteratons.yaml", "icp:\n  iteratons: 12\n");
  EXPECT_THAT(config_error_of([&] { load_slam_config(path); }),
              HasSubstr(path + ": unknown key 'icp.iteratons'"));
  const std::string section = write("section.yaml", "ICP:\n  iterations: 12\n");
  EXPECT_THAT(config_error_of([&] { load_slam_config(section); }),
              HasSubstr(section + ": unknown key 'ICP'"));
}

TEST_F(YamlFileTest, SlamConfigRejectsOutOfRangeValues) {
  const std::string path = write("zero.yaml", "icp:\n  iterations: 0\n");
  EXPECT_THAT(config_error_of([&] { load_slam_config(path); }),
              HasSubstr("key 'icp.iterations': expected an integer >= 1, got '0'"));
  const std::string negative = write("negative.yaml", "map:\n  keyframe_lateral: -0.5\n");
  EXPECT_THAT(config_error_of([&] { load_slam_config(negative); }),
              HasSubstr("key 'map.keyframe_lateral': expected a number >= 0, got '-0.5'"));
}

TEST_F(YamlFileTest, SlamConfigRejectsADuplicateKey) {
  const std::string path = write("twice.yaml", "icp:\n  iterations: 5\n  iterations: 6\n");
  EXPECT_THAT(config_error_of([&] { load_slam_config(path); }),
              HasSubstr("duplicate key 'icp.iterations'"));
}

TEST(SlamConfigOverride, SetsOneValue) {
  SlamConfig config;
  apply_slam_config_override(config, "icp.iterations=12");
  apply_slam_config_override(config, "nearest_neighbour.index=exact");
  apply_slam_config_override(config, "map.keyframe_lateral=0.75");
  EXPECT_EQ(config.icp.iterations, 12);
  EXPECT_EQ(config.nearest_neighbour.index, IndexKind::Exact);
  EXPECT_EQ(config.map.keyframe_lateral, 0.75);
  EXPECT_EQ(config.icp.max_translation, SlamConfig{}.icp.max_translation);
}

TEST(SlamConfigOverride, RejectsUnknownKeysAndBadValues) {
  SlamConfig config;
  EXPECT_THAT(config_error_of([&] { apply_slam_config_override(config, "icp.iteratons=12"); }),
              HasSubstr("unknown key 'icp.iteratons'"));
  EXPECT_THAT(config_error_of([&] { apply_slam_config_override(config, "icp.iterations=many"); }),
              HasSubstr("key 'icp.iterations': expected an integer >= 1, got 'many'"));
  EXPECT_THAT(config_error_of([&] { apply_slam_config_override(config, "icp.iterations=2.5"); }),
              HasSubstr("got '2.5'"));
  EXPECT_THAT(
      config_error_of([&] { apply_slam_config_override(config, "nearest_neighbour.index=kd"); }),
      HasSubstr("expected one of 'flann', 'exact', 'brute', got 'kd'"));
  EXPECT_THAT(config_error_of([&] { apply_slam_config_override(config, "icp.iterations"); }),
              HasSubstr("expected section.key=value"));
  EXPECT_EQ(config.icp.iterations, SlamConfig{}.icp.iterations);  // failures change nothing
}

TEST(LaunchFile, ShippedDemoListsTheSixProcesses) {
  const LaunchFile launch =
      load_launch_file(std::string(UAVSLAM_SOURCE_DIR) + "/config/launch/demo.yaml");
  std::vector<std::string> names;
  for (const LaunchedProcess& p : launch.processes) names.push_back(p.name);
  EXPECT_THAT(names, ::testing::ElementsAre("ground_station", "map_server", "recorder",
                                            "slam_matcher", "imu_bridge", "lidar_driver"));
  EXPECT_TRUE(launch.processes.back().until_exit);
  EXPECT_EQ(launch.processes.front().executable, "ground_station");
  EXPECT_TRUE(launch.processes.front().node_options);
}

TEST(LaunchFile, EveryShippedLaunchFileLoads) {
  const std::filesystem::path dir = std::string(UAVSLAM_SOURCE_DIR) + "/config/launch";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    EXPECT_FALSE(load_launch_file(entry.path().string()).processes.empty()) << entry.path();
    ++files;
  }
  EXPECT_GE(files, 3);
}

TEST_F(YamlFileTest, LaunchFileReadsEveryKey) {
  const LaunchFile launch = load_launch_file(write("launch_full.yaml", R"(
domain: 7
vehicle: uav3
participant_profile: uavslam_link_gcs
log_dir: /tmp/logs
stop_grace_s: 2.5
start_delay_s: 0
processes:
  - {name: a, executable: /bin/true, args: [-x, "{start_at}"], node_options: false, until_exit: true}
)"));
  EXPECT_EQ(launch.domain, 7);
  EXPECT_EQ(launch.vehicle, "uav3");
  EXPECT_EQ(launch.participant_profile, "uavslam_link_gcs");
  EXPECT_EQ(launch.log_dir, "/tmp/logs");
  EXPECT_DOUBLE_EQ(launch.stop_grace_s, 2.5);
  EXPECT_DOUBLE_EQ(launch.start_delay_s, 0.0);
  ASSERT_EQ(launch.processes.size(), 1u);
  EXPECT_EQ(launch.processes[0].executable, "/bin/true");
  EXPECT_THAT(launch.processes[0].args, ::testing::ElementsAre("-x", "{start_at}"));
  EXPECT_FALSE(launch.processes[0].node_options);
  EXPECT_TRUE(launch.processes[0].until_exit);
}

TEST_F(YamlFileTest, LaunchFileErrorsNameTheKey) {
  const std::string typo = write("launch_typo.yaml", "processes:\n  - {name: a, arg: [x]}\n");
  EXPECT_THAT(config_error_of([&] { load_launch_file(typo); }), HasSubstr("processes[0].arg"));
  const std::string twice = write("launch_twice.yaml", "processes: [{name: a}, {name: a}]\n");
  EXPECT_THAT(config_error_of([&] { load_launch_file(twice); }),
              HasSubstr("a second process named 'a'"));
  const std::string none = write("launch_none.yaml", "processes: []\n");
  EXPECT_THAT(config_error_of([&] { load_launch_file(none); }), HasSubstr("no process to launch"));
  const std::string domain = write("launch_domain.yaml", "domain: 300\nprocesses: [{name: a}]\n");
  EXPECT_THAT(config_error_of([&] { load_launch_file(domain); }), HasSubstr("300"));
}

}  // namespace
}  // namespace uavslam::io
