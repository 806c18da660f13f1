// The subcommands of the `uavslam` tool. Each registers itself on the app; its callback sets the
// process exit code (0 done, 1 failed, 130 stopped by Ctrl-C).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/SlamConfig.hpp"

namespace uavslam::cli {

void add_simulate_command(CLI::App& app, int& exit_code);
void add_eval_command(CLI::App& app, int& exit_code);
void add_sweep_command(CLI::App& app, int& exit_code);
void add_launch_command(CLI::App& app, int& exit_code);
void add_report_command(CLI::App& app, int& exit_code);
void add_run_command(CLI::App& app, int& exit_code);
void add_offline_command(CLI::App& app, int& exit_code);

// --config FILE (optional; the seed's defaults otherwise) and then each --set key=value.
// config_help says what the file is for in this subcommand.
void add_slam_config_options(CLI::App& cmd, std::string& config,
                             std::vector<std::string>& overrides, const std::string& config_help);
SlamConfig load_config(const std::string& path, const std::vector<std::string>& overrides);
// A configuration shipped in config/ (e.g. "slam_2d_logs.yaml"): the installed one beside bin/,
// else the source tree's.
std::string shipped_config(const std::string& name);
// The configuration for a CARMEN log when none is given: the real 2D logs' one (the seed's mode
// is `--config config/seed.yaml`).
inline constexpr char kLogsConfig[] = "slam_2d_logs.yaml";

}  // namespace uavslam::cli
