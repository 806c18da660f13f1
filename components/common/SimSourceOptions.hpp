// The options of a sensor process whose data comes from a source: `sim` (the flight simulator
// along a scenario) for now; real devices and logs come later.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/RealTimePacer.hpp"
#include "io/YamlReader.hpp"

namespace uavslam::process {

struct SimSourceOptions {
  std::string source = "sim";
  std::string scenario = "config/scenarios/demo.yaml";
  double rate = 1.0;             // times real time
  int wait_for_subscribers = 0;  // hold the first sample until this many readers have matched
  double duration = 0.0;         // s of the flight to publish from its start; 0: all of it
  double start_at = 0.0;  // system-clock time (s since the epoch) the flight starts; 0: when ready
};

// Registers --source, --scenario, --rate, --wait-for-subscribers, --duration, --start-at.
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
