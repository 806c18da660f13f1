// Reads a simulated flight (config/scenarios/*.yaml) into a sim::Scenario, checking every value.
#pragma once

#include <optional>
#include <string>

#include "sensor/LidarSpec.hpp"
#include "sim/Scenario.hpp"

namespace uavslam::io {

// Required: world.room {min, max} and trajectory.waypoints (>= 2 of {t, position, yaw_deg});
// everything else defaults to the values in sim/Scenario.hpp, `name` to the file's stem.
// Throws ConfigError (io/YamlReader.hpp) naming the file, key and value at fault.
sim::Scenario load_scenario(const std::string& path);

// What a sensor file says: the scanner, and for a scenario file also where its flight takes off.
struct SensorFile {
  SensorDescription sensor;
  std::optional<Vec3> take_off;  // a scenario's first waypoint; none for a sensor file
};

// Where the matcher finds its scanner: a sensor file that holds only `name` and a `lidar` section
// (config/sensors/*.yaml: a real vehicle's scanner), or a scenario (load_scenario), whose
// simulated world and flight are not needed beyond the take-off point.
SensorFile load_sensor(const std::string& path);

}  // namespace uavslam::io
