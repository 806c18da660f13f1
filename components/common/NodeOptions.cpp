#include "common/NodeOptions.hpp"

#include "dds/Profiles.hpp"

namespace uavslam::process {

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
}

std::string profiles_path(const NodeOptions& options) {
  return options.qos_file.empty() ? dds::default_profiles_path() : options.qos_file;
}

bool unset(const CLI::App& app, const std::string& flag) {
  return app.get_option(flag)->count() == 0;
}

std::optional<io::YamlReader> apply_node_config(const CLI::App& app, NodeOptions& options,
                                                const std::string& node) {
  if (options.config_file.empty()) return std::nullopt;
  const io::YamlReader file = io::YamlReader::from_file(options.config_file, "node config");
  if (const auto dds = file.find("dds")) {
    dds->expect_keys_only({"domain", "vehicle", "qos_file", "participant_profile"});
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
  return file.find(node);
}

}  // namespace uavslam::process
