#include "io/LaunchFile.hpp"

#include <set>

#include "io/YamlReader.hpp"

namespace uavslam::io {
namespace {

std::vector<std::string> string_list(const YamlReader& node) {
  std::vector<std::string> values;
  for (const YamlReader& element : node.elements()) values.push_back(element.as_string());
  return values;
}

LaunchedProcess read_process(const YamlReader& node) {
  node.expect_keys_only({"name", "executable", "args", "node_options", "until_exit"});
  LaunchedProcess p;
  p.name = node.get_string("name");
  if (p.name.empty()) node.at("name").fail_expected("a process name");
  p.executable = node.get_string_or("executable", p.name);
  if (const auto args = node.find("args")) p.args = string_list(*args);
  p.node_options = node.get_bool_or("node_options", p.node_options);
  p.until_exit = node.get_bool_or("until_exit", p.until_exit);
  return p;
}

}  // namespace

LaunchFile load_launch_file(const std::string& path) {
  const YamlReader file = YamlReader::from_file(path, "launch");
  file.expect_keys_only({"domain", "vehicle", "participant_profile", "log_dir", "stop_grace_s",
                         "start_delay_s", "processes"});
  LaunchFile launch;
  launch.domain = file.get_int_or("domain", launch.domain, NumberRange::between(0, 232));
  launch.vehicle = file.get_string_or("vehicle", launch.vehicle);
  launch.participant_profile =
      file.get_string_or("participant_profile", launch.participant_profile);
  launch.log_dir = file.get_string_or("log_dir", launch.log_dir);
  launch.stop_grace_s =
      file.get_double_or("stop_grace_s", launch.stop_grace_s, NumberRange::positive());
  launch.start_delay_s =
      file.get_double_or("start_delay_s", launch.start_delay_s, NumberRange::non_negative());
  const YamlReader processes = file.at("processes");
  std::set<std::string> names;
  for (const YamlReader& node : processes.elements()) {
    LaunchedProcess p = read_process(node);
    if (!names.insert(p.name).second)
      node.at("name").fail("a second process named '" + p.name + "'");
    launch.processes.push_back(std::move(p));
  }
  if (launch.processes.empty()) processes.fail("no process to launch");
  return launch;
}

}  // namespace uavslam::io
