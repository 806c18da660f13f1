// Reads a simulated flight (config/scenarios/*.yaml) into a sim::Scenario, checking every value.
#pragma once

#include <string>

#include "sim/Scenario.hpp"

namespace uavslam::io {

// Required: world.room {min, max} and trajectory.waypoints (>= 2 of {t, position, yaw_deg});
// everything else defaults to the values in sim/Scenario.hpp, `name` to the file's stem.
// Throws ConfigError (io/YamlReader.hpp) naming the file, key and value at fault.
sim::Scenario load_scenario(const std::string& path);

// Where the matcher finds its scanner: a scenario (load_scenario), or a sensor file that holds only
// `name` and a `lidar` section (config/sensors/*.yaml: a real vehicle's scanner, with no simulated
// world or flight; the scenario it returns has no waypoints).
sim::Scenario load_sensor(const std::string& path);

}  // namespace uavslam::io
