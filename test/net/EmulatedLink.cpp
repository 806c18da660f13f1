#include "EmulatedLink.hpp"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "common/ChildProcess.hpp"

extern char** environ;

namespace uavslam::net {
namespace {

constexpr const char* kUavAddress = "10.200.0.1";
constexpr const char* kGcsAddress = "10.200.0.2";
constexpr const char* kQueueNumber = "1";
// A burst the qdisc sends at line speed; 10 ms of the rate, at least a few full-size frames.
constexpr double kTbfBurstSeconds = 0.01;
constexpr int kTbfMinBurstBytes = 15000;
// How long a packet may wait in the tbf queue before it is dropped (WiFi buffers are deep).
constexpr const char* kTbfLatency = "200ms";
constexpr std::chrono::seconds kEmulatorStartTimeout{5};

std::atomic<int> links_made{0};

struct CommandResult {
  int status = -1;     // exit status; 127 + when it could not start
  std::string output;  // stdout and stderr
};

// Runs argv (argv[0] a path) to its end and collects its output.
CommandResult run(const std::vector<std::string>& argv) {
  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) return {-1, std::strerror(errno)};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 1);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 2);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int spawn_error = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_fds[1]);
  CommandResult result;
  char buffer[4096];
  ssize_t length = 0;
  while ((length = read(pipe_fds[0], buffer, sizeof buffer)) > 0 ||
         (length < 0 && errno == EINTR)) {
    if (length > 0) result.output.append(buffer, static_cast<std::size_t>(length));
  }
  close(pipe_fds[0]);
  if (spawn_error != 0) return {127, argv[0] + ": " + std::strerror(spawn_error)};
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

std::string joined(const std::vector<std::string>& argv) {
  std::string text;
  for (const std::string& a : argv) text += (text.empty() ? "" : " ") + a;
  return text;
}

// Runs argv and throws, naming the command and its output, when it fails.
std::string must_run(const std::vector<std::string>& argv) {
  const CommandResult result = run(argv);
  if (result.status != 0) {
    throw std::runtime_error("`" + joined(argv) + "` failed (" + std::to_string(result.status) +
                             "): " + result.output);
  }
  return result.output;
}

std::string find_tool(const std::string& name) {
  // `ip netns exec` and posix_spawn need a path; root's tools are often outside a test's PATH.
  std::string path = "/usr/sbin:/sbin:/usr/bin:/bin";
  if (const char* env = std::getenv("PATH")) path = std::string(env) + ":" + path;
  std::stringstream directories(path);
  std::string directory;
  while (std::getline(directories, directory, ':')) {
    const std::string candidate = directory + "/" + name;
    if (!directory.empty() && access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

std::vector<std::string> namespace_names(const std::string& ip) {
  std::vector<std::string> names;
  std::stringstream lines(run({ip, "netns", "list"}).output);
  std::string line;
  while (std::getline(lines, line)) {
    const std::string name = line.substr(0, line.find(' '));
    if (!name.empty()) names.push_back(name);
  }
  return names;
}

// Kills what still runs in namespace `name` (it would keep the namespace alive), then deletes it.
void delete_namespace(const std::string& ip, const std::string& name) {
  std::stringstream pids(run({ip, "netns", "pids", name}).output);
  for (pid_t pid = 0; pids >> pid;) {
    if (pid > 0 && pid != getpid()) kill(pid, SIGKILL);
  }
  run({ip, "netns", "delete", name});
}

std::string format_number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// Waits until the kernel reports the interface running (LOWER_UP): a veth's carrier comes up
// after both ends are up, delayed by the kernel's link watch (up to a second), and Fast DDS
// leaves out an interface that is not running when a participant starts ("All whitelist
// interfaces were filtered out").
void wait_until_running(const std::string& ip, const std::string& name, const std::string& dev) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (run({ip, "-n", name, "link", "show", "dev", dev}).output.find("LOWER_UP") ==
         std::string::npos) {
    if (std::chrono::steady_clock::now() > deadline) {
      throw std::runtime_error(dev + " in " + name + " is not running after 5 s");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

std::string EmulatedLink::tool_path(const std::string& name) {
  return find_tool(name);
}

EmulatedLink::Tools EmulatedLink::find_tools() {
  return {find_tool("ip"), find_tool("tc"), find_tool("iptables")};
}

LinkAvailability EmulatedLink::available(const std::string& emulator_path) {
  if (geteuid() != 0) return {false, "needs root (network namespaces, veth pairs, iptables)"};
  const Tools tools = find_tools();
  if (tools.ip.empty()) return {false, "no `ip` (iproute2) on PATH"};
  if (tools.tc.empty()) return {false, "no `tc` (iproute2) on PATH"};
  if (tools.iptables.empty()) return {false, "no `iptables` (apt-get install iptables)"};
  if (access(emulator_path.c_str(), X_OK) != 0) {
    return {false, "link_emulator not built at " + emulator_path};
  }
  const std::string probe =
      "usl" + std::to_string(getpid()) + "p" + std::to_string(links_made.fetch_add(1));
  const CommandResult added = run({tools.ip, "netns", "add", probe});
  if (added.status != 0) return {false, "cannot create a network namespace: " + added.output};
  const CommandResult rule =
      run({tools.ip, "netns", "exec", probe, tools.iptables, "-w", "5", "-A", "OUTPUT", "-o", "lo",
           "-j", "NFQUEUE", "--queue-num", kQueueNumber});
  delete_namespace(tools.ip, probe);
  if (rule.status != 0) return {false, "iptables cannot add an NFQUEUE rule: " + rule.output};
  if (!std::filesystem::exists("/proc/net/netfilter/nfnetlink_queue")) {
    run({find_tool("modprobe"), "-q", "nfnetlink_queue"});
    if (!std::filesystem::exists("/proc/net/netfilter/nfnetlink_queue")) {
      return {false, "the kernel has no NFQUEUE support (module nfnetlink_queue)"};
    }
  }
  return {true, ""};
}

std::vector<std::string> EmulatedLink::sweep_stale() {
  const std::string ip = find_tools().ip;
  std::vector<std::string> removed;
  if (ip.empty()) return removed;
  const std::regex ours("^usl([0-9]+)[a-z].*");
  for (const std::string& name : namespace_names(ip)) {
    std::smatch match;
    if (!std::regex_match(name, match, ours)) continue;
    const pid_t owner = static_cast<pid_t>(std::stol(match[1].str()));
    if (owner == getpid() || kill(owner, 0) == 0 || errno != ESRCH) continue;
    delete_namespace(ip, name);
    removed.push_back(name);
  }
  return removed;
}

EmulatedLink::EmulatedLink(const LinkSpec& spec, const std::string& emulator_path,
                           const std::string& log_dir)
    : tools_(find_tools()) {
  if (tools_.ip.empty() || tools_.tc.empty() || tools_.iptables.empty()) {
    throw std::runtime_error("EmulatedLink needs ip, tc and iptables");
  }
  sweep_stale();
  const std::string stem =
      "usl" + std::to_string(getpid()) + "n" + std::to_string(links_made.fetch_add(1));
  uav_namespace_ = stem + "u";
  gcs_namespace_ = stem + "g";
  try {
    build(spec, emulator_path, log_dir);
  } catch (...) {
    tear_down();
    throw;
  }
}

EmulatedLink::~EmulatedLink() {
  tear_down();
}

void EmulatedLink::build(const LinkSpec& spec, const std::string& emulator_path,
                         const std::string& log_dir) {
  const std::string& ip = tools_.ip;
  for (Host host : {Host::kUav, Host::kGcs}) must_run({ip, "netns", "add", namespace_name(host)});
  // Created directly inside the namespaces: the host's own interfaces never see the pair.
  must_run({ip, "link", "add", interface_name(Host::kUav), "netns", uav_namespace_, "type", "veth",
            "peer", "name", interface_name(Host::kGcs), "netns", gcs_namespace_});
  for (Host host : {Host::kUav, Host::kGcs}) {
    const std::string& name = namespace_name(host);
    must_run({ip, "-n", name, "addr", "add", address(host) + "/24", "dev", interface_name(host)});
    must_run({ip, "-n", name, "link", "set", interface_name(host), "up"});
    must_run({ip, "-n", name, "link", "set", "lo", "up"});
    if (spec.rate_mbit > 0.0) {
      const double bytes_per_second = spec.rate_mbit * 1e6 / 8.0;
      const int burst =
          std::max(kTbfMinBurstBytes, static_cast<int>(bytes_per_second * kTbfBurstSeconds));
      must_run({tools_.tc, "-n", name, "qdisc", "add", "dev", interface_name(host), "root", "tbf",
                "rate", format_number(spec.rate_mbit) + "mbit", "burst", std::to_string(burst),
                "latency", kTbfLatency});
    }
    if (spec.delay_ms > 0.0 || spec.jitter_ms > 0.0 || spec.record_traffic) {
      // The emulator binds its queue first: a packet sent to an unbound queue is dropped.
      start_emulator(host, spec, emulator_path, log_dir);
      iptables(host, {"-A", "OUTPUT", "-o", interface_name(host), "-j", "NFQUEUE", "--queue-num",
                      kQueueNumber});
    } else if (spec.loss > 0.0) {
      iptables(host, {"-A", "INPUT", "-i", interface_name(host), "-m", "statistic", "--mode",
                      "random", "--probability", format_number(spec.loss), "-j", "DROP"});
    }
  }
  for (Host host : {Host::kUav, Host::kGcs}) {
    wait_until_running(ip, namespace_name(host), interface_name(host));
  }
}

void EmulatedLink::start_emulator(Host host, const LinkSpec& spec, const std::string& emulator_path,
                                  const std::string& log_dir) {
  std::vector<std::string> argv = exec_prefix(host);
  const std::uint64_t seed = spec.seed + (host == Host::kUav ? 1 : 0);
  for (const std::string& arg :
       {emulator_path, std::string("--queue"), std::string(kQueueNumber), std::string("--delay-ms"),
        format_number(spec.delay_ms), std::string("--jitter-ms"), format_number(spec.jitter_ms),
        std::string("--loss"), format_number(spec.loss), std::string("--seed"),
        std::to_string(seed)}) {
    argv.push_back(arg);
  }
  if (spec.record_traffic) {
    std::string& file = host == Host::kUav ? uav_traffic_file_ : gcs_traffic_file_;
    file = log_dir + "/link_traffic_" + namespace_name(host) + ".json";
    argv.insert(argv.end(), {"--traffic", file});
  }
  const std::string log = log_dir + "/link_emulator_" + namespace_name(host) + ".log";
  emulators_.push_back(std::make_unique<process::ChildProcess>(argv, log, true));
  process::ChildProcess& emulator = *emulators_.back();
  const auto deadline = std::chrono::steady_clock::now() + kEmulatorStartTimeout;
  while (emulator.log().find(" ready") == std::string::npos) {
    if (!emulator.running() || std::chrono::steady_clock::now() > deadline) {
      throw std::runtime_error("link_emulator did not start in " + namespace_name(host) + ": " +
                               emulator.log());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

void EmulatedLink::iptables(Host host, const std::vector<std::string>& rule) const {
  // Inside the namespace: its tables are its own, the host's are never touched.
  std::vector<std::string> argv = exec_prefix(host);
  argv.insert(argv.end(), {tools_.iptables, "-w", "5"});
  argv.insert(argv.end(), rule.begin(), rule.end());
  must_run(argv);
}

const std::string& EmulatedLink::namespace_name(Host host) const {
  return host == Host::kUav ? uav_namespace_ : gcs_namespace_;
}

std::string EmulatedLink::interface_name(Host host) const {
  return host == Host::kUav ? "uav0" : "gcs0";
}

std::string EmulatedLink::address(Host host) const {
  return host == Host::kUav ? kUavAddress : kGcsAddress;
}

std::vector<std::string> EmulatedLink::exec_prefix(Host host) const {
  return {tools_.ip, "netns", "exec", namespace_name(host)};
}

int EmulatedLink::open_socket(Host host, int type) const {
  // setns changes the namespace of the calling thread only; a socket keeps the namespace it was
  // made in, so a short-lived thread makes it and this process's own threads stay on the host.
  const std::string path = "/run/netns/" + namespace_name(host);
  int socket_fd = -1;
  int error = 0;
  std::thread maker([&] {
    const int namespace_fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (namespace_fd < 0 || setns(namespace_fd, CLONE_NEWNET) != 0) {
      error = errno;
    } else {
      socket_fd = socket(AF_INET, type | SOCK_CLOEXEC, 0);
      if (socket_fd < 0) error = errno;
    }
    if (namespace_fd >= 0) close(namespace_fd);
  });
  maker.join();
  if (socket_fd < 0) {
    throw std::runtime_error("cannot open a socket in " + path + ": " + std::strerror(error));
  }
  return socket_fd;
}

void EmulatedLink::begin_outage() {
  if (outage_active_) return;
  for (Host host : {Host::kUav, Host::kGcs}) {
    iptables(host, {"-I", "INPUT", "1", "-i", interface_name(host), "-j", "DROP"});
  }
  outage_active_ = true;
}

void EmulatedLink::end_outage() {
  if (!outage_active_) return;
  for (Host host : {Host::kUav, Host::kGcs}) {
    iptables(host, {"-D", "INPUT", "-i", interface_name(host), "-j", "DROP"});
  }
  outage_active_ = false;
}

void EmulatedLink::outage(std::chrono::milliseconds length) {
  begin_outage();
  std::this_thread::sleep_for(length);
  end_outage();
}

std::string EmulatedLink::stop_emulators() {
  for (const auto& emulator : emulators_) {
    emulator->stop(std::chrono::seconds(5));
    emulator_output_ += emulator->log();
  }
  emulators_.clear();
  return emulator_output_;
}

std::string EmulatedLink::traffic_file(Host from) const {
  return from == Host::kUav ? uav_traffic_file_ : gcs_traffic_file_;
}

void EmulatedLink::tear_down() noexcept {
  // Each step on its own: whatever fails, the namespaces (and with them veths and rules) must go.
  try {
    stop_emulators();
  } catch (...) {
  }
  for (const std::string& name : {uav_namespace_, gcs_namespace_}) {
    try {
      if (!name.empty()) delete_namespace(tools_.ip, name);
    } catch (...) {
    }
  }
}

}  // namespace uavslam::net
