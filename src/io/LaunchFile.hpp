// A launch file: the processes of one deployment (the demo on a laptop, the on-board set of a UAV)
// with their arguments, started in order by `uavslam launch` and stopped in reverse order.
//
//   domain: 42              # passed to every process as --domain (and vehicle as --vehicle)
//   vehicle: uav1
//   participant_profile: uavslam_link_uav  # passed as --participant-profile (default: the
//                                          # processes' own, uavslam_loopback)
//   log_dir: out/demo/logs  # one <name>.log per process
//   stop_grace_s: 10        # SIGINT, then SIGKILL after this long
//   start_delay_s: 3        # "{start_at}" in args: the system-clock time this long after launch
//   processes:
//     - name: slam_matcher  # the executable, looked up beside `uavslam`, then on PATH
//       args: [--sensor, config/scenarios/demo.yaml]
//     - name: lidar_driver
//       args: [--scenario, config/scenarios/demo.yaml, --start-at, "{start_at}"]
//       until_exit: true    # the run ends when this process ends by itself
#pragma once

#include <string>
#include <vector>

namespace uavslam::io {

struct LaunchedProcess {
  std::string name;        // label in logs and messages
  std::string executable;  // defaults to name
  std::vector<std::string> args;
  bool node_options = true;  // prepend --domain and --vehicle
  bool until_exit = false;   // its own exit ends the run
};

struct LaunchFile {
  int domain = 0;
  std::string vehicle = "uav1";
  std::string participant_profile;  // empty: each process's default
  std::string log_dir = "out/logs";
  double stop_grace_s = 10.0;
  double start_delay_s = 3.0;  // the simulated sensors' shared start, after discovery
  std::vector<LaunchedProcess> processes;
};

// Throws ConfigError naming file, key and value: unknown keys, a process without a name, two
// processes of one name, no process at all.
LaunchFile load_launch_file(const std::string& path);

}  // namespace uavslam::io
