#include "common/SimSourceOptions.hpp"

#include "common/NodeOptions.hpp"

namespace uavslam::process {
namespace {

constexpr const char* kCarmenPrefix = "carmen:";
constexpr const char* kMcapPrefix = "mcap:";

bool has_file_prefix(const std::string& source, const std::string& prefix) {
  return source.rfind(prefix, 0) == 0 && source.size() > prefix.size();
}

std::optional<std::string> file_after(const std::string& source, const std::string& prefix) {
  if (!has_file_prefix(source, prefix)) return std::nullopt;
  return source.substr(prefix.size());
}

// Empty when `source` names a source this process can read, else what is wrong with it.
std::string source_problem(const std::string& source, const std::vector<std::string>& devices) {
  if (source == "sim" || has_file_prefix(source, kCarmenPrefix) ||
      has_file_prefix(source, kMcapPrefix)) {
    return {};
  }
  std::string expected = "sim, carmen:FILE (a CARMEN log), mcap:FILE (an MCAP recording)";
  for (const std::string& prefix : devices) {
    if (has_file_prefix(source, prefix)) return {};
    expected += ", " + prefix + "ADDRESS";
  }
  return "expected " + expected + ", got '" + source + "'";
}

}  // namespace

std::optional<std::string> carmen_log_path(const SimSourceOptions& options) {
  return file_after(options.source, kCarmenPrefix);
}

std::optional<std::string> mcap_log_path(const SimSourceOptions& options) {
  return file_after(options.source, kMcapPrefix);
}

void add_sim_source_options(CLI::App& app, SimSourceOptions& options) {
  app.add_option("--source", options.source,
                 "where the data comes from: sim (the flight simulator along --scenario), "
                 "carmen:FILE (replay a CARMEN log's laser scans, e.g. the Freiburg benchmark's "
                 "intel.clf, at the recorded pace times --rate), mcap:FILE (replay an MCAP "
                 "recording's messages at their log_time spacing times --rate), or a device "
                 "(see the process's description)")
      ->check(CLI::Validator(
          [&options](std::string& value) { return source_problem(value, options.device_prefixes); },
          "sim|carmen:FILE|mcap:FILE|DEVICE", "source"))
      ->capture_default_str();
  app.add_option("--scenario", options.scenario, "scenario YAML for the sim source")
      ->capture_default_str();
  app.add_option("--rate", options.rate,
                 "publish this many times faster than real time (carmen, mcap: than recorded)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--wait-for-subscribers", options.wait_for_subscribers,
                 "publish only once this many readers have matched (waits up to 30 s)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--duration", options.duration,
                 "publish only the first this many seconds of the flight or log (0: all of it)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--start-at", options.start_at,
                 "system-clock time (s since 1970) at which the flight's first sample is due; give "
                 "lidar_driver and imu_bridge the same value so their streams share one timeline "
                 "(sim: samples overdue when the process is ready are skipped; carmen: every scan "
                 "is published, the late ones counted); 0: start when ready")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-scans", options.max_scans,
                 "carmen, mcap: replay only the log's first this many scans (0: all of them)")
      ->capture_default_str();
}

RealTimePacer make_pacer(const SimSourceOptions& options, double flight_start) {
  if (options.start_at <= 0.0) return RealTimePacer(options.rate);
  return RealTimePacer(options.rate, options.start_at, flight_start);
}

bool within_duration(const SimSourceOptions& options, double flight_start, double stamp) {
  return options.duration <= 0.0 || stamp - flight_start <= options.duration;
}

void apply_sim_source_config(const CLI::App& app, const io::YamlReader& section,
                             SimSourceOptions& options,
                             const std::vector<std::string>& extra_keys) {
  std::vector<std::string> keys{"source",   "scenario", "rate",     "wait_for_subscribers",
                                "duration", "start_at", "max_scans"};
  keys.insert(keys.end(), extra_keys.begin(), extra_keys.end());
  section.expect_keys_only(keys);
  if (unset(app, "--source") && section.has("source")) {
    const io::YamlReader source = section.at("source");
    options.source = source.as_string();
    const std::string problem = source_problem(options.source, options.device_prefixes);
    if (!problem.empty()) source.fail(problem);
  }
  if (unset(app, "--scenario")) {
    options.scenario = section.get_string_or("scenario", options.scenario);
  }
  if (unset(app, "--rate")) {
    options.rate = section.get_double_or("rate", options.rate, io::NumberRange::positive());
  }
  if (unset(app, "--wait-for-subscribers")) {
    options.wait_for_subscribers = section.get_int_or(
        "wait_for_subscribers", options.wait_for_subscribers, io::NumberRange::at_least(0));
  }
  if (unset(app, "--start-at")) {
    options.start_at =
        section.get_double_or("start_at", options.start_at, io::NumberRange::non_negative());
  }
  if (unset(app, "--duration")) {
    options.duration =
        section.get_double_or("duration", options.duration, io::NumberRange::non_negative());
  }
  if (unset(app, "--max-scans")) {
    options.max_scans = static_cast<std::size_t>(section.get_int_or(
        "max_scans", static_cast<int>(options.max_scans), io::NumberRange::at_least(0)));
  }
}

}  // namespace uavslam::process
