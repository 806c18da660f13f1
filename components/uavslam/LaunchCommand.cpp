// uavslam launch: start the processes of a launch file (config/launch/*.yaml) in order, each in
// its own process group with its output in <log_dir>/<name>.log; when a process marked until_exit
// ends (or one fails, or Ctrl-C), stop the others in reverse order with SIGINT so each flushes its
// outputs, and report every exit code.
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>

#include "Commands.hpp"
#include "common/ChildProcess.hpp"
#include "common/StopRequest.hpp"
#include "io/FileError.hpp"
#include "io/LaunchFile.hpp"

namespace uavslam::cli {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

struct LaunchOptions {
  std::string file;
  int domain = -1;                  // -1: the launch file's
  std::string participant_profile;  // empty: the launch file's
  std::string log_dir;
};

struct Running {
  io::LaunchedProcess spec;
  std::unique_ptr<process::ChildProcess> child;
  bool ended = false;  // announced as ended
};

// Beside this executable first (build/bin holds every process), then on PATH.
std::string find_executable(const std::string& name) {
  if (name.find('/') != std::string::npos) return name;
  std::error_code error;
  const fs::path beside = fs::read_symlink("/proc/self/exe", error).parent_path() / name;
  if (!error && access(beside.c_str(), X_OK) == 0) return beside.string();
  if (const char* path = std::getenv("PATH")) {
    std::string dirs = path;
    for (std::size_t start = 0, end; start <= dirs.size(); start = end + 1) {
      end = dirs.find(':', start);
      if (end == std::string::npos) end = dirs.size();
      const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
      if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
  }
  throw std::runtime_error("no executable '" + name + "' beside uavslam or on PATH");
}

// "{start_at}" in an argument: one system-clock time for every process of the run.
std::string substitute(std::string arg, const std::string& start_at) {
  const std::string key = "{start_at}";
  for (auto at = arg.find(key); at != std::string::npos; at = arg.find(key, at)) {
    arg.replace(at, key.size(), start_at);
  }
  return arg;
}

std::vector<std::string> command_line(const io::LaunchFile& launch, const io::LaunchedProcess& p,
                                      const std::string& start_at) {
  std::vector<std::string> argv{find_executable(p.executable)};
  if (p.node_options) {
    argv.insert(argv.end(),
                {"--domain", std::to_string(launch.domain), "--vehicle", launch.vehicle});
    if (!launch.participant_profile.empty()) {
      argv.insert(argv.end(), {"--participant-profile", launch.participant_profile});
    }
  }
  for (const std::string& arg : p.args) argv.push_back(substitute(arg, start_at));
  return argv;
}

std::string start_time(double delay_s) {
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  return std::to_string(std::chrono::duration<double>(now).count() + delay_s);
}

std::string last_line(const std::string& text) {
  std::size_t end = text.find_last_not_of("\r\n");
  if (end == std::string::npos) return "";
  std::size_t begin = text.find_last_of("\r\n", end);
  return text.substr(begin == std::string::npos ? 0 : begin + 1, end - (begin + 1) + 1);
}

// Why the run ends: the until_exit process ended by itself, a process failed, or a stop request.
// Other processes that end cleanly (a sensor at the end of its data) leave the rest running.
enum class RunEnd { Finished, Failed, Stopped };

RunEnd supervise(std::vector<Running>& processes) {
  while (!process::stop_requested()) {
    for (Running& r : processes) {
      if (r.ended || r.child->running()) continue;
      r.ended = true;
      const int code = r.child->exit_code();
      std::cerr << "launch: " << r.spec.name << " ended (exit " << code << ")\n";
      if (code != 0) return RunEnd::Failed;
      if (r.spec.until_exit) return RunEnd::Finished;
    }
    std::this_thread::sleep_for(50ms);
  }
  return RunEnd::Stopped;
}

int run_launch(const LaunchOptions& o) {
  io::LaunchFile launch = io::load_launch_file(o.file);
  if (o.domain >= 0) launch.domain = o.domain;
  if (!o.participant_profile.empty()) launch.participant_profile = o.participant_profile;
  if (!o.log_dir.empty()) launch.log_dir = o.log_dir;
  fs::create_directories(launch.log_dir);

  const std::string start_at = start_time(launch.start_delay_s);
  std::vector<Running> processes;
  for (const io::LaunchedProcess& spec : launch.processes) {
    const std::string log = (fs::path(launch.log_dir) / (spec.name + ".log")).string();
    auto child =
        std::make_unique<process::ChildProcess>(command_line(launch, spec, start_at), log, true);
    if (!child->started()) throw std::runtime_error("cannot start " + spec.name);
    std::cerr << "launch: started " << spec.name << " (pid " << child->pid() << "), log " << log
              << "\n";
    processes.push_back({spec, std::move(child)});
  }
  const RunEnd end = supervise(processes);

  const auto grace = std::chrono::milliseconds(static_cast<long>(launch.stop_grace_s * 1000));
  bool all_clean = true;
  for (auto it = processes.rbegin(); it != processes.rend(); ++it) {
    const int code = it->child->stop(grace);
    all_clean = all_clean && code == 0;
    std::cerr << "launch: " << it->spec.name << " exit " << code << ": "
              << last_line(it->child->log()) << "\n";
  }
  if (end == RunEnd::Stopped) return 130;
  return end == RunEnd::Finished && all_clean ? 0 : 1;
}

}  // namespace

void add_launch_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<LaunchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "launch",
      "start the processes of a launch file (config/launch/*.yaml) in order, stop them in reverse "
      "order when the until_exit process ends or on Ctrl-C");
  cmd->add_option("file", options->file, "launch file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--domain", options->domain,
                  "DDS domain id for every process (overrides the file)")
      ->check(CLI::Range(0, 232));
  cmd->add_option("--participant-profile", options->participant_profile,
                  "DDS participant profile for every process (overrides the file), e.g. "
                  "uavslam_link_uav on a vehicle talking to a ground station");
  cmd->add_option("--log-dir", options->log_dir, "where <name>.log go (overrides the file)");
  cmd->callback([options, &exit_code] { exit_code = run_launch(*options); });
}

}  // namespace uavslam::cli
