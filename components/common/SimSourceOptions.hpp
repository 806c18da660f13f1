// The options of a sensor process whose data comes from a source: `sim` (the flight simulator
// along a scenario), `carmen:FILE` (a recorded CARMEN log replayed at its recorded pace) or
// `mcap:FILE` (an MCAP recording replayed at its log_time spacing), or a real device the process
// names in `device_prefixes` (lidar_driver: scip2:, scip2tcp:; imu_bridge: mavlink:), whose
// address the process itself checks when it opens it.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/RealTimePacer.hpp"
#include "io/YamlReader.hpp"

namespace uavslam::process {

struct SimSourceOptions {
  std::string source = "sim";  // "sim", "carmen:FILE" or "mcap:FILE"
  std::string scenario = "config/scenarios/demo.yaml";
  double rate = 1.0;             // times real time
  int wait_for_subscribers = 0;  // hold the first sample until this many readers have matched
  double duration = 0.0;         // s of the flight to publish from its start; 0: all of it
  double start_at = 0.0;  // system-clock time (s since the epoch) the flight starts; 0: when ready
  std::size_t max_scans = 0;  // carmen, mcap: replay only this many scans; 0: all of them
  std::vector<std::string> device_prefixes;  // this process's device sources, e.g. "scip2:"
};

// The log of a `carmen:FILE` source; nullopt for `sim`.
std::optional<std::string> carmen_log_path(const SimSourceOptions& options);
// The recording of an `mcap:FILE` source; nullopt for the others.
std::optional<std::string> mcap_log_path(const SimSourceOptions& options);

// Registers --source, --scenario, --rate, --wait-for-subscribers, --duration, --start-at,
// --max-scans; `options.device_prefixes` must be set before (the --source check reads them).
void add_sim_source_options(CLI::App& app, SimSourceOptions& options);
// Fills what the command line left unset from the process's config section.
// `extra_keys`: the process's own keys in the same section.
void apply_sim_source_config(const CLI::App& app, const io::YamlReader& section,
                             SimSourceOptions& options,
                             const std::vector<std::string>& extra_keys = {});

// The pacer of a sim source: a shared timeline from --start-at, if given (RealTimePacer.hpp).
RealTimePacer make_pacer(const SimSourceOptions& options, double flight_start);

// True while a sample stamped `stamp` belongs to the part of the flight to publish.
bool within_duration(const SimSourceOptions& options, double flight_start, double stamp);

}  // namespace uavslam::process
