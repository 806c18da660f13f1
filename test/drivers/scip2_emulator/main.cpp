// scip2_emulator: a Hokuyo UTM-30LX-like sensor for testing lidar_driver without hardware. It
// speaks SCIP 2.0 (EmulatedHokuyo.hpp) on a pseudo-terminal, reachable through a symlink as a
// udev rule would make one (--pty-link), or on TCP 127.0.0.1:PORT (--tcp-port; 0 picks one), and
// serves the simulator's scans of a scenario at 40 Hz. Faults on request: wrong checksums,
// garbage, truncated replies, a silence, a disconnect (the pty or socket closed, back after a
// while, like an unplugged cable). --truth writes every scan sent: index, true host time (the
// sweep's start, system clock), sensor stamp, simulated scan index.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "EmulatedHokuyo.hpp"
#include "io/ScenarioFile.hpp"
#include "sim/FlightSimulator.hpp"

namespace {

volatile std::sig_atomic_t stop = 0;

double now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

struct Plan {
  std::string pty_link;
  int tcp_port = -1;
  double silence_at = -1.0, silence_for = 0.0;        // s after start
  double disconnect_at = -1.0, disconnect_for = 0.0;  // s after start
};

// The device end: a pty master behind a symlink, or a listening socket and its one client.
class Device {
 public:
  explicit Device(const Plan& plan) : plan_(plan) {}
  ~Device() { close_all(); }

  bool open_device() { return plan_.tcp_port >= 0 ? listen_tcp() : open_pty(); }
  void close_all() {
    for (int* fd : {&io_, &listener_, &pty_slave_}) {
      if (*fd >= 0) ::close(*fd);
      *fd = -1;
    }
    if (!plan_.pty_link.empty()) ::unlink(plan_.pty_link.c_str());
  }
  // The fd to talk on (-1: no client yet); accepts a TCP client when one waits.
  int io() {
    if (io_ < 0 && listener_ >= 0) {
      io_ = ::accept4(listener_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
      if (io_ >= 0) std::cerr << "scip2_emulator: client connected\n";
    }
    return io_;
  }
  void drop_client() {
    if (listener_ >= 0 && io_ >= 0) {
      ::close(io_);
      io_ = -1;
    }
  }
  void send(const std::string& bytes) {
    if (io_ < 0 || bytes.empty()) return;
    // A host that does not read loses bytes, as with a real sensor; never block.
    [[maybe_unused]] const ssize_t n = ::write(io_, bytes.data(), bytes.size());
  }

 private:
  bool open_pty() {
    io_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (io_ < 0 || ::grantpt(io_) != 0 || ::unlockpt(io_) != 0) return false;
    const std::string slave = ::ptsname(io_);
    // Holding the slave open keeps the master readable while the driver reconnects; raw mode so
    // the line discipline neither echoes nor translates.
    pty_slave_ = ::open(slave.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
    termios tty{};
    ::tcgetattr(pty_slave_, &tty);
    ::cfmakeraw(&tty);
    ::tcsetattr(pty_slave_, TCSANOW, &tty);
    ::unlink(plan_.pty_link.c_str());
    if (::symlink(slave.c_str(), plan_.pty_link.c_str()) != 0) return false;
    std::cout << "scip2_emulator: ready on " << plan_.pty_link << " -> " << slave << std::endl;
    return true;
  }
  bool listen_tcp() {
    listener_ = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    const int yes = 1;
    ::setsockopt(listener_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // loopback only, never the network
    address.sin_port =
        htons(static_cast<std::uint16_t>(bound_port_ > 0 ? bound_port_ : plan_.tcp_port));
    if (::bind(listener_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
        ::listen(listener_, 1) != 0) {
      return false;
    }
    socklen_t length = sizeof address;
    ::getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length);
    bound_port_ = ntohs(address.sin_port);
    std::cout << "scip2_emulator: ready on 127.0.0.1:" << bound_port_ << std::endl;
    return true;
  }

  Plan plan_;
  int io_ = -1;
  int listener_ = -1;
  int pty_slave_ = -1;
  int bound_port_ = 0;
};

std::vector<std::vector<float>> simulated_scans(const std::string& scenario_path) {
  uavslam::sim::FlightSimulator simulator(uavslam::io::load_scenario(scenario_path));
  std::vector<std::vector<float>> scans;
  uavslam::Scan scan;
  while (simulator.next_scan(scan)) scans.push_back(scan.ranges);
  return scans;
}

int run(const Plan& plan, const uavslam::test::EmulatorOptions& options,
        const std::string& scenario, const std::string& truth_path) {
  const double start = now_s();
  uavslam::test::EmulatedHokuyo sensor(options, simulated_scans(scenario), start);
  std::ofstream truth;
  if (!truth_path.empty()) truth.open(truth_path);
  truth << std::fixed << std::setprecision(6);
  Device device(plan);
  if (!device.open_device()) {
    std::cerr << "scip2_emulator: cannot open the device end\n";
    return 1;
  }
  bool disconnected = false;
  while (!stop) {
    const double now = now_s();
    const double t = now - start;
    const bool silent = t >= plan.silence_at && t < plan.silence_at + plan.silence_for;
    if (plan.disconnect_at >= 0 && !disconnected && t >= plan.disconnect_at &&
        t < plan.disconnect_at + plan.disconnect_for) {
      std::cerr << "scip2_emulator: disconnecting\n";
      device.close_all();
      sensor.reset_link();
      disconnected = true;
    } else if (disconnected && t >= plan.disconnect_at + plan.disconnect_for) {
      std::cerr << "scip2_emulator: reconnecting\n";
      if (!device.open_device()) return 1;
      disconnected = false;
    }
    const int fd = disconnected ? -1 : device.io();
    const double wait = std::min(sensor.next_due() - now, 0.005);
    pollfd p{fd, POLLIN, 0};
    ::poll(&p, fd >= 0 ? 1 : 0, static_cast<int>(std::max(0.0, wait) * 1e3));
    if (fd < 0) continue;
    if (!silent && (p.revents & (POLLIN | POLLHUP | POLLERR))) {
      char buffer[1024];
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n > 0) {
        device.send(sensor.receive(std::string(buffer, static_cast<std::size_t>(n)), now_s()));
      } else if (n == 0 || (n < 0 && errno != EAGAIN && errno != EIO)) {
        std::cerr << "scip2_emulator: client gone\n";
        device.drop_client();
        sensor.reset_link();
        continue;
      }
    }
    if (silent) continue;
    device.send(sensor.due_scans(now_s(), [&](const uavslam::test::SentScan& s) {
      if (truth) {
        truth << s.index << ' ' << s.true_time << ' ' << s.stamp_ms << ' ' << s.sim_scan << '\n';
        truth.flush();
      }
    }));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"scip2_emulator: a Hokuyo UTM-30LX speaking SCIP 2.0 on a pty or TCP, for tests"};
  Plan plan;
  uavslam::test::EmulatorOptions options;
  std::string scenario = "config/scenarios/short.yaml";
  std::string truth;
  auto* pty = app.add_option("--pty-link", plan.pty_link, "make a pty, symlinked at this path");
  auto* tcp = app.add_option("--tcp-port", plan.tcp_port, "listen on 127.0.0.1:PORT (0: any)");
  pty->excludes(tcp);
  app.add_option("--scenario", scenario, "scenario whose simulated scans to serve")
      ->capture_default_str();
  app.add_option("--truth", truth, "write every scan sent: index, true time, stamp, sim scan");
  app.add_option("--drift-ppm", options.drift_ppm, "sensor clock rate error");
  app.add_option("--offset-ms", options.offset_ms, "sensor clock at start");
  app.add_option("--jitter-ms", options.jitter_ms, "random extra send delay, up to this");
  app.add_option("--bad-checksum-every", options.bad_checksum_every, "data blocks");
  app.add_option("--garbage-every", options.garbage_every, "scans");
  app.add_option("--truncate-every", options.truncate_every, "scans");
  app.add_flag("!--no-intensity", options.intensity, "refuse ME (distance + intensity)");
  app.add_option("--silence-at", plan.silence_at, "s after start: stop answering");
  app.add_option("--silence-for", plan.silence_for, "s");
  app.add_option("--disconnect-at", plan.disconnect_at, "s after start: close the pty/socket");
  app.add_option("--disconnect-for", plan.disconnect_for, "s until it comes back");
  CLI11_PARSE(app, argc, argv);
  if (plan.pty_link.empty() && plan.tcp_port < 0) {
    std::cerr << "scip2_emulator: give --pty-link PATH or --tcp-port PORT\n";
    return 2;
  }
  std::signal(SIGINT, [](int) { stop = 1; });
  std::signal(SIGTERM, [](int) { stop = 1; });
  std::signal(SIGPIPE, SIG_IGN);
  return run(plan, options, scenario, truth);
}
