// Reads the SLAM parameters (config/slam.yaml) into a SlamConfig, and applies command-line
// overrides such as `--set icp.iterations=12`. The YAML sections and keys mirror the struct.
#pragma once

#include <string>

#include "core/SlamConfig.hpp"

namespace uavslam::io {

// Every key is optional (default: the struct's); unknown keys and out-of-range values throw
// ConfigError (io/YamlReader.hpp) naming the file, key and value at fault.
SlamConfig load_slam_config(const std::string& path);

// `assignment` is "section.key=value" with the file's key names and checks, e.g.
// "icp.iterations=12" or "nearest_neighbour.index=exact".
void apply_slam_config_override(SlamConfig& config, const std::string& assignment);

}  // namespace uavslam::io
