#include "common/NodeOptions.hpp"

#include <sched.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "dds/Profiles.hpp"
#include "dds/Topics.hpp"

namespace uavslam::process {
namespace {

const std::vector<std::string> kTopics{
    dds::kScanTopic, dds::kImuTopic,           dds::kPoseTopic,         dds::kMapPointsTopic,
    dds::kMapTopic,  dds::kKeyframePosesTopic, dds::kMatcherStatusTopic};

bool is_topic(const std::string& base) {
  return std::find(kTopics.begin(), kTopics.end(), base) != kTopics.end();
}

// "--profile scan=my_sensor_reader" -> profiles["scan"].
void parse_profile_flags(NodeOptions& options) {
  for (const std::string& flag : options.profile_flags) {
    const std::size_t eq = flag.find('=');
    const std::string topic = flag.substr(0, eq);
    if (eq == std::string::npos || eq + 1 == flag.size() || !is_topic(topic)) {
      throw io::ConfigError("--profile '" + flag +
                            "': expected TOPIC=PROFILE with TOPIC one of scan, imu, pose, "
                            "map_points, map, keyframe_poses, matcher_status");
    }
    options.profiles[topic] = flag.substr(eq + 1);
  }
}

}  // namespace

void enter_realtime(int priority) {
  if (priority <= 0) return;
  sched_param param{};
  param.sched_priority = priority;
  if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
    throw io::ConfigError("--realtime-priority " + std::to_string(priority) +
                          ": cannot switch to SCHED_FIFO: " + std::strerror(errno) +
                          " (needs root or CAP_SYS_NICE)");
  }
}

std::string NodeOptions::profile(const std::string& base, const std::string& class_default) const {
  const auto chosen = profiles.find(base);
  return chosen == profiles.end() ? class_default : chosen->second;
}

void add_node_options(CLI::App& app, NodeOptions& options) {
  app.add_option("--config", options.config_file,
                 "node YAML: its `dds` section and this process's section (flags win)")
      ->check(CLI::ExistingFile);
  app.add_option("--domain", options.domain, "DDS domain id")
      ->check(CLI::Range(0, 232))
      ->capture_default_str();
  app.add_option("--vehicle", options.vehicle, "vehicle id: prefixes the topic names")
      ->capture_default_str();
  app.add_option("--qos", options.qos_file,
                 "Fast DDS XML profiles (default: qos/uavslam_profiles.xml, or $UAVSLAM_QOS_FILE)");
  app.add_option("--participant-profile", options.participant_profile,
                 "participant profile in the XML file")
      ->capture_default_str();
  app.add_option("--realtime-priority", options.realtime_priority,
                 "run with the SCHED_FIFO real-time scheduler at this priority (1-99; 0: normal); "
                 "needs root or CAP_SYS_NICE")
      ->check(CLI::Range(0, 99));
  app.add_option("--profile", options.profile_flags,
                 "TOPIC=PROFILE: the writer/reader profile of the XML file for one topic, "
                 "instead of its class's (repeatable; e.g. scan=sensor_reader)");
}

std::string profiles_path(const NodeOptions& options) {
  return options.qos_file.empty() ? dds::default_profiles_path() : options.qos_file;
}

bool unset(const CLI::App& app, const std::string& flag) {
  return app.get_option(flag)->count() == 0;
}

std::optional<io::YamlReader> apply_node_config(const CLI::App& app, NodeOptions& options,
                                                const std::string& node) {
  parse_profile_flags(options);
  if (options.config_file.empty()) {
    enter_realtime(options.realtime_priority);
    return std::nullopt;
  }
  const io::YamlReader file = io::YamlReader::from_file(options.config_file, "node config");
  if (const auto dds = file.find("dds")) {
    dds->expect_keys_only(
        {"domain", "vehicle", "qos_file", "participant_profile", "profiles", "realtime_priority"});
    if (unset(app, "--realtime-priority")) {
      options.realtime_priority = dds->get_int_or("realtime_priority", options.realtime_priority,
                                                  io::NumberRange::between(0, 99));
    }
    if (const auto profiles = dds->find("profiles")) {
      profiles->expect_keys_only(kTopics);
      for (const std::string& topic : kTopics) {
        // The command line wins over the file.
        if (profiles->has(topic) && !options.profiles.count(topic)) {
          options.profiles[topic] = profiles->get_string(topic);
        }
      }
    }
    if (unset(app, "--domain")) {
      options.domain = dds->get_int_or("domain", options.domain, io::NumberRange::between(0, 232));
    }
    if (unset(app, "--vehicle")) options.vehicle = dds->get_string_or("vehicle", options.vehicle);
    if (unset(app, "--qos")) options.qos_file = dds->get_string_or("qos_file", options.qos_file);
    if (unset(app, "--participant-profile")) {
      options.participant_profile =
          dds->get_string_or("participant_profile", options.participant_profile);
    }
  }
  enter_realtime(options.realtime_priority);
  return file.find(node);
}

}  // namespace uavslam::process
