// The options every DDS process takes: which domain and vehicle, which QoS profile file and
// participant profile, and an optional YAML config whose `dds` section and own section fill in
// whatever the command line did not set (flags win over the file).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "io/YamlReader.hpp"

namespace uavslam::process {

struct NodeOptions {
  int domain = 0;
  std::string vehicle = "uav1";
  std::string qos_file;  // empty: dds::default_profiles_path()
  std::string participant_profile = "uavslam_loopback";
  std::string config_file;
  int realtime_priority = 0;               // SCHED_FIFO priority, 1..99; 0: the normal scheduler
  std::vector<std::string> profile_flags;  // --profile TOPIC=PROFILE, as given
  std::map<std::string, std::string> profiles;  // topic (base name) -> writer/reader profile

  // The writer or reader profile for topic `base` ("scan", "pose", ...): the one chosen by
  // --profile or the config's dds.profiles, else `class_default` (e.g. "sensor_reader").
  std::string profile(const std::string& base, const std::string& class_default) const;
};

// Registers --config, --domain, --vehicle, --qos, --participant-profile, --profile,
// --realtime-priority.
void add_node_options(CLI::App& app, NodeOptions& options);

// After parsing: reads options.config_file (if any), fills the node options the command line left
// unset from its `dds` section, switches the process to real-time scheduling if asked (before any
// DDS thread exists, so they all inherit it), and returns the section named `node` (e.g.
// "lidar_driver") for the process's own keys. Throws io::ConfigError naming file, key and value,
// or why the scheduler refused.
std::optional<io::YamlReader> apply_node_config(const CLI::App& app, NodeOptions& options,
                                                const std::string& node);

// Switches the whole process to the SCHED_FIFO real-time scheduler at `priority` (1..99; 0 does
// nothing): on this loaded 2-core machine it cut the matcher's scan-to-pose p99 from ~4.5 ms to
// ~1.3 ms (docs/speed.md). Threads created afterwards inherit it. Throws io::ConfigError saying
// why the scheduler refused (it needs root or CAP_SYS_NICE).
void enter_realtime(int priority);

// The QoS profile file to load: --qos, the config's dds.qos_file, or the default.
std::string profiles_path(const NodeOptions& options);

// True when the flag was not given on the command line (so a config file may set it).
bool unset(const CLI::App& app, const std::string& flag);

}  // namespace uavslam::process
