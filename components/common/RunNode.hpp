// A process's main body with the project's exit codes: 0 done, 1 failed at run time, 2 bad
// configuration (config file, QoS profiles, command line), each with a message naming the cause.
#pragma once

#include <functional>
#include <optional>

#include <CLI/CLI.hpp>

namespace uavslam::process {

// Parses the command line. Nothing when the process should go on; else its exit code: 0 after
// --help, 2 after a bad flag or value (CLI11's message names it).
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv);

int run_node(const char* name, const std::function<int()>& body);

}  // namespace uavslam::process
