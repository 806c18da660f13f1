#include "io/ScenarioFile.hpp"

#include <filesystem>
#include <sstream>

#include "io/YamlReader.hpp"
#include "sim/World.hpp"

namespace uavslam::io {

namespace {

std::string shown(const Vec3& v) {
  std::ostringstream text;
  text << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return text.str();
}

sim::Box read_box(const YamlReader& reader) {
  reader.expect_keys_only({"min", "max"});
  sim::Box box;
  box.min = reader.get_vec3("min");
  box.max = reader.get_vec3("max");
  if (!(box.min.array() < box.max.array()).all()) {
    reader.fail("expected min < max on every axis, got min " + shown(box.min) + " and max " +
                shown(box.max));
  }
  return box;
}

// A vertical extent `z: [z0, z1]`, z0 < z1.
Eigen::Vector2d read_z_range(const YamlReader& reader) {
  const YamlReader z_range = reader.at("z");
  const Eigen::Vector2d z = z_range.as_vec2();
  if (!(z.x() < z.y())) z_range.fail_expected("[z0, z1] with z0 < z1");
  return z;
}

// What a cylinder and a round wall share: `center: [x, y]`, `radius` > 0, `z: [z0, z1]`.
template <typename Round>
Round read_round(const YamlReader& reader) {
  Round round;
  round.center = reader.at("center").as_vec2();
  round.radius = reader.get_double("radius", NumberRange::positive());
  const Eigen::Vector2d z = read_z_range(reader);
  round.z0 = z.x();
  round.z1 = z.y();
  return round;
}

sim::Cylinder read_cylinder(const YamlReader& reader) {
  reader.expect_keys_only({"center", "radius", "z"});
  return read_round<sim::Cylinder>(reader);
}

sim::ArcWall read_arc(const YamlReader& reader) {
  reader.expect_keys_only({"center", "radius", "from_deg", "to_deg", "z"});
  sim::ArcWall arc = read_round<sim::ArcWall>(reader);
  arc.from_deg = reader.get_double_or("from_deg", arc.from_deg);
  arc.to_deg = reader.get_double_or("to_deg", arc.to_deg,
                                    NumberRange::between(arc.from_deg, arc.from_deg + 360.0));
  return arc;
}

// A walking person: `path: [[x, y], ...]` (two points at least), `speed`, `start` (m along the
// path at t = 0), `radius`, `height`.
sim::Walker read_walker(const YamlReader& reader) {
  reader.expect_keys_only({"path", "speed", "start", "radius", "height"});
  sim::Walker walker;
  const YamlReader path = reader.at("path");
  for (const YamlReader& point : path.elements()) walker.path.push_back(point.as_vec2());
  if (walker.path.size() < 2) path.fail_expected("a path of two points [x, y] at least");
  walker.speed = reader.get_double_or("speed", walker.speed, NumberRange::positive());
  walker.start = reader.get_double_or("start", walker.start, NumberRange::non_negative());
  walker.radius = reader.get_double_or("radius", walker.radius, NumberRange::positive());
  walker.height = reader.get_double_or("height", walker.height, NumberRange::positive());
  return walker;
}

sim::WorldSpec read_world(const YamlReader& reader) {
  reader.expect_keys_only({"room", "boxes", "cylinders", "arcs", "people"});
  sim::WorldSpec world;
  world.room = read_box(reader.at("room"));
  if (const auto boxes = reader.find("boxes")) {
    for (const YamlReader& box : boxes->elements()) world.boxes.push_back(read_box(box));
  }
  if (const auto cylinders = reader.find("cylinders")) {
    for (const YamlReader& cylinder : cylinders->elements()) {
      world.cylinders.push_back(read_cylinder(cylinder));
    }
  }
  if (const auto arcs = reader.find("arcs")) {
    for (const YamlReader& arc : arcs->elements()) world.arcs.push_back(read_arc(arc));
  }
  if (const auto people = reader.find("people")) {
    for (const YamlReader& walker : people->elements()) world.people.push_back(read_walker(walker));
  }
  return world;
}

sim::Waypoint read_waypoint(const YamlReader& reader, const sim::World& world) {
  reader.expect_keys_only({"t", "position", "yaw_deg"});
  sim::Waypoint waypoint;
  waypoint.t = reader.get_double("t");
  const YamlReader position = reader.at("position");
  waypoint.position = position.as_vec3();
  if (!world.is_free(waypoint.position)) {
    position.fail_expected("a point inside the room and outside every obstacle");
  }
  waypoint.yaw_deg = reader.get_double_or("yaw_deg", 0.0);
  return waypoint;
}

sim::Vehicle read_vehicle(const YamlReader& trajectory) {
  const std::string vehicle = trajectory.get_string_or("vehicle", "multirotor");
  if (vehicle == "multirotor") return sim::Vehicle::multirotor;
  if (vehicle == "ground") return sim::Vehicle::ground;
  trajectory.at("vehicle").fail_expected("multirotor or ground");
}

std::vector<sim::Waypoint> read_waypoints(const YamlReader& reader, const sim::World& world) {
  reader.expect_keys_only({"vehicle", "waypoints"});
  const YamlReader list = reader.at("waypoints");
  std::vector<sim::Waypoint> waypoints;
  for (const YamlReader& item : list.elements()) {
    waypoints.push_back(read_waypoint(item, world));
    const std::size_t n = waypoints.size();
    if (n >= 2 && !(waypoints[n - 1].t > waypoints[n - 2].t)) {
      std::ostringstream expected;
      expected << "a time after the previous waypoint's " << waypoints[n - 2].t;
      item.at("t").fail_expected(expected.str());
    }
  }
  if (waypoints.size() < 2) list.fail_expected("a list of at least 2 waypoints");
  return waypoints;
}

FloorMirrorSpec read_floor_mirror(const YamlReader& reader, int beams) {
  reader.expect_keys_only({"beams", "spread_deg"});
  FloorMirrorSpec mirror;
  mirror.beams =
      reader.get_int_or("beams", mirror.beams, NumberRange::between(0, static_cast<double>(beams)));
  mirror.spread_deg =
      reader.get_double_or("spread_deg", mirror.spread_deg, NumberRange::between(0.0, 180.0));
  return mirror;
}

void read_mount(const YamlReader& reader, LidarSpec& lidar) {
  reader.expect_keys_only({"position", "rpy_deg"});
  lidar.mount_position = reader.get_vec3_or("position", lidar.mount_position);
  lidar.mount_rpy_deg = reader.get_vec3_or("rpy_deg", lidar.mount_rpy_deg);
}

LidarSpec read_lidar(const YamlReader& reader) {
  reader.expect_keys_only({"beams", "fov_deg", "rate_hz", "min_range", "max_range",
                           "range_noise_std", "sweep_seconds", "mount", "floor_mirror", "rings",
                           "vertical_fov_deg"});
  LidarSpec lidar;
  lidar.beams = reader.get_int_or("beams", lidar.beams, NumberRange::at_least(1));
  lidar.fov_deg = reader.get_double_or("fov_deg", lidar.fov_deg, {0.0, 360.0, true});
  lidar.rate_hz = reader.get_double_or("rate_hz", lidar.rate_hz, NumberRange::positive());
  lidar.min_range = reader.get_double_or("min_range", lidar.min_range, NumberRange::non_negative());
  lidar.max_range = reader.get_double_or("max_range", lidar.max_range,
                                         NumberRange::greater_than(lidar.min_range));
  lidar.range_noise_std =
      reader.get_double_or("range_noise_std", lidar.range_noise_std, NumberRange::non_negative());
  lidar.sweep_seconds = reader.get_double_or("sweep_seconds", lidar.sweep_seconds,
                                             NumberRange::between(0.0, 1.0 / lidar.rate_hz));
  if (const auto mount = reader.find("mount")) read_mount(*mount, lidar);
  if (const auto mirror = reader.find("floor_mirror")) {
    lidar.floor_mirror = read_floor_mirror(*mirror, lidar.beams);
  }
  lidar.rings = reader.get_int_or("rings", lidar.rings, NumberRange::at_least(1));
  lidar.vertical_fov_deg = reader.get_double_or("vertical_fov_deg", lidar.vertical_fov_deg,
                                                NumberRange::between(0.0, 180.0));
  return lidar;
}

sim::ImuSpec read_imu(const YamlReader& reader) {
  reader.expect_keys_only({"rate_hz", "orientation_noise_std_deg", "yaw_drift_deg_per_min",
                           "yaw_drift_changes", "gyro_noise_std", "accel_noise_std", "accel_bias"});
  sim::ImuSpec imu;
  imu.rate_hz = reader.get_double_or("rate_hz", imu.rate_hz, NumberRange::positive());
  imu.orientation_noise_std_deg = reader.get_double_or(
      "orientation_noise_std_deg", imu.orientation_noise_std_deg, NumberRange::non_negative());
  imu.yaw_drift_deg_per_min =
      reader.get_double_or("yaw_drift_deg_per_min", imu.yaw_drift_deg_per_min);
  if (const auto changes = reader.find("yaw_drift_changes")) {
    for (const YamlReader& item : changes->elements()) {
      item.expect_keys_only({"t", "deg_per_min"});
      const double after = imu.yaw_drift_changes.empty() ? 0.0 : imu.yaw_drift_changes.back().t;
      imu.yaw_drift_changes.push_back(
          {item.get_double("t", NumberRange::greater_than(after)), item.get_double("deg_per_min")});
    }
  }
  imu.gyro_noise_std =
      reader.get_double_or("gyro_noise_std", imu.gyro_noise_std, NumberRange::non_negative());
  imu.accel_noise_std =
      reader.get_double_or("accel_noise_std", imu.accel_noise_std, NumberRange::non_negative());
  imu.accel_bias = reader.get_vec3_or("accel_bias", imu.accel_bias);
  return imu;
}

sim::FaultSpec read_faults(const YamlReader& reader) {
  reader.expect_keys_only({"late_scan_every", "late_scan_s"});
  sim::FaultSpec faults;
  faults.late_scan_every =
      reader.get_int_or("late_scan_every", faults.late_scan_every, NumberRange::non_negative());
  faults.late_scan_s =
      reader.get_double_or("late_scan_s", faults.late_scan_s, NumberRange::non_negative());
  return faults;
}

sim::VelocitySpec read_velocity(const YamlReader& reader) {
  reader.expect_keys_only({"rate_hz", "noise_std"});
  sim::VelocitySpec velocity;
  velocity.rate_hz = reader.get_double_or("rate_hz", velocity.rate_hz, NumberRange::positive());
  velocity.noise_std =
      reader.get_double_or("noise_std", velocity.noise_std, NumberRange::positive());
  return velocity;
}

sim::WheelOdometrySpec read_odometry(const YamlReader& reader) {
  reader.expect_keys_only({"translation_scale_error", "turn_scale_error", "translation_noise",
                           "turn_noise", "turn_per_metre_noise"});
  sim::WheelOdometrySpec odometry;
  const NumberRange scale = NumberRange::between(-0.5, 0.5);
  odometry.translation_scale_error =
      reader.get_double_or("translation_scale_error", odometry.translation_scale_error, scale);
  odometry.turn_scale_error =
      reader.get_double_or("turn_scale_error", odometry.turn_scale_error, scale);
  odometry.translation_noise = reader.get_double_or("translation_noise", odometry.translation_noise,
                                                    NumberRange::non_negative());
  odometry.turn_noise =
      reader.get_double_or("turn_noise", odometry.turn_noise, NumberRange::non_negative());
  odometry.turn_per_metre_noise = reader.get_double_or(
      "turn_per_metre_noise", odometry.turn_per_metre_noise, NumberRange::non_negative());
  return odometry;
}

}  // namespace

sim::Scenario load_scenario(const std::string& path) {
  const YamlReader root = YamlReader::from_file(path, "scenario");
  root.expect_keys_only(
      {"name", "seed", "world", "trajectory", "lidar", "imu", "velocity", "faults", "odometry"});
  sim::Scenario scenario;
  scenario.name = root.get_string_or("name", std::filesystem::path(path).stem().string());
  scenario.seed = root.get_uint64_or("seed", scenario.seed);
  scenario.world = read_world(root.at("world"));
  scenario.waypoints = read_waypoints(root.at("trajectory"), sim::World(scenario.world));
  scenario.vehicle = read_vehicle(root.at("trajectory"));
  if (const auto lidar = root.find("lidar")) scenario.lidar = read_lidar(*lidar);
  if (const auto imu = root.find("imu")) scenario.imu = read_imu(*imu);
  if (const auto velocity = root.find("velocity")) scenario.velocity = read_velocity(*velocity);
  if (const auto faults = root.find("faults")) scenario.faults = read_faults(*faults);
  if (const auto odometry = root.find("odometry")) scenario.odometry = read_odometry(*odometry);
  return scenario;
}

SensorFile load_sensor(const std::string& path) {
  const YamlReader root = YamlReader::from_file(path, "sensor");
  if (root.find("world")) {
    const sim::Scenario scenario = load_scenario(path);
    return {{scenario.name, scenario.lidar}, scenario.waypoints.front().position};
  }
  root.expect_keys_only({"name", "lidar"});
  SensorFile file;
  file.sensor.name = root.get_string_or("name", std::filesystem::path(path).stem().string());
  file.sensor.lidar = read_lidar(root.at("lidar"));
  return file;
}

}  // namespace uavslam::io
