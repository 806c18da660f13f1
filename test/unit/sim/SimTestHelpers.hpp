// Small worlds, flights and file paths shared by the sim unit tests.
#pragma once

#include <string>
#include <vector>

#include "io/ScenarioFile.hpp"
#include "sim/Scenario.hpp"

namespace uavslam::sim::testing {

inline std::string scenario_path(const std::string& name) {
  return std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml";
}

inline Scenario shipped_scenario(const std::string& name) {
  return io::load_scenario(scenario_path(name));
}

inline const std::vector<std::string>& shipped_scenario_names() {
  static const std::vector<std::string> names = {
      "demo",           "corridor",        "yaw_drift",        "short",
      "plain_corridor", "flow_corridor",   "late_scans",       "two_rooms",
      "drift_change",   "biased_corridor", "corridor_follower"};
  return names;
}

// An empty 10 x 8 x 3 m room.
inline WorldSpec empty_room() {
  WorldSpec world;
  world.room.min = Vec3(0.0, 0.0, 0.0);
  world.room.max = Vec3(10.0, 8.0, 3.0);
  return world;
}

// A hover at `position` with heading `yaw_deg` from t = 0 to t = duration.
inline std::vector<Waypoint> hover(const Vec3& position, double yaw_deg, double duration) {
  return {{0.0, position, yaw_deg}, {duration, position, yaw_deg}};
}

}  // namespace uavslam::sim::testing
