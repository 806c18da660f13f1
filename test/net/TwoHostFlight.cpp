#include "TwoHostFlight.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <thread>

#include "io/TumFile.hpp"

namespace uavslam::net {
namespace {

namespace fs = std::filesystem;

// The number before `label` in a process's log ("801 scans received"), -1 when absent.
long count_before(const std::string& log, const std::string& label) {
  std::smatch match;
  if (!std::regex_search(log, match, std::regex("(\\d+) " + label))) return -1;
  return std::stol(match[1]);
}

double system_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

std::vector<double> read_arrivals(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // header
  std::vector<double> times;
  while (std::getline(in, line)) {
    unsigned long long seq = 0;
    double stamp = 0.0, received_at = 0.0;
    if (std::sscanf(line.c_str(), "%llu,%lf,%lf", &seq, &stamp, &received_at) == 3) {
      times.push_back(received_at);
    }
  }
  return times;
}

// Resident memory of a process in kB (/proc/PID/status VmRSS); -1 when it is gone.
long resident_kb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  }
  return -1;
}

std::string format_time(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6f", seconds);
  return text;
}

}  // namespace

double FlightResult::matched_share() const {
  if (scans_published <= 0 || poses_published < 0) return 0.0;
  return static_cast<double>(poses_published) / static_cast<double>(scans_published);
}

std::optional<double> FlightResult::poses_resumed_after(double t) const {
  for (double arrival : pose_arrivals) {
    if (arrival >= t) return arrival - t;
  }
  return std::nullopt;
}

TwoHostFlight::TwoHostFlight(const FlightSpec& spec, const EmulatedLink* link)
    : spec_(spec), link_(link) {
  fs::create_directories(spec_.out_dir);
}

TwoHostFlight::~TwoHostFlight() {
  // The sensors first, the ground station last, as the launcher stops a deployment.
  for (auto it = processes_.rbegin(); it != processes_.rend(); ++it) {
    (*it)->stop(std::chrono::seconds(5));
  }
}

std::string TwoHostFlight::out(const std::string& name) const {
  return (fs::path(spec_.out_dir) / name).string();
}

process::ChildProcess& TwoHostFlight::launch(Host host, const std::string& name,
                                             std::vector<std::string> flags) {
  std::vector<std::string> argv;
  if (link_) argv = link_->exec_prefix(host);
  const std::string profile = !link_               ? "uavslam_loopback"
                              : host == Host::kUav ? "uavslam_link_uav"
                                                   : "uavslam_link_gcs";
  argv.insert(argv.end(), {spec_.bin_dir + "/" + name, "--domain", std::to_string(spec_.domain),
                           "--participant-profile", profile});
  argv.insert(argv.end(), flags.begin(), flags.end());
  processes_.push_back(std::make_unique<process::ChildProcess>(argv, out(name + ".log")));
  if (!processes_.back()->started()) throw std::runtime_error("cannot start " + name);
  return *processes_.back();
}

std::vector<std::string> TwoHostFlight::sensor_flags(int subscribers) const {
  std::vector<std::string> flags{"--scenario",
                                 spec_.scenario,
                                 "--rate",
                                 std::to_string(spec_.rate),
                                 "--wait-for-subscribers",
                                 std::to_string(subscribers),
                                 "--start-at",
                                 format_time(start_at_)};
  if (spec_.duration_s > 0)
    flags.insert(flags.end(), {"--duration", std::to_string(spec_.duration_s)});
  return flags;
}

void TwoHostFlight::start(double lead_s) {
  start_at_ = system_now() + lead_s;
  if (link_ && spec_.discovery_server) start_discovery_server();
  const bool ground = spec_.matcher_host == Host::kGcs;
  std::vector<std::string> station{"--out", out("gcs")};
  if (!spec_.station_latency) station.push_back("--no-latency");
  if (spec_.station) station_ = &launch(Host::kGcs, "ground_station", station);
  if (spec_.map_server)
    map_server_ = &launch(spec_.matcher_host, "map_server", {"--out", out("map")});
  std::vector<std::string> matcher{"--sensor", spec_.scenario};
  matcher.insert(matcher.end(), spec_.matcher_flags.begin(), spec_.matcher_flags.end());
  if (ground) matcher.insert(matcher.end(), {"--profile", "scan=sensor_link_reader"});
  matcher_ = &launch(spec_.matcher_host, "slam_matcher", matcher);
  imu_ = &launch(Host::kUav, "imu_bridge", sensor_flags(1));
  std::vector<std::string> lidar = sensor_flags(spec_.station && spec_.station_latency ? 2 : 1);
  lidar.insert(lidar.end(), {"--groundtruth", out("groundtruth.tum")});
  if (ground) lidar.insert(lidar.end(), {"--profile", "scan=sensor_link_writer"});
  lidar_ = &launch(Host::kUav, "lidar_driver", lidar);
}

// As uav_discovery_server.yaml runs it: the server on the UAV at 10.200.0.1:11811, from the
// uavslam_discovery_server profile.
void TwoHostFlight::start_discovery_server() {
  std::vector<std::string> argv = link_->exec_prefix(Host::kUav);
  argv.insert(argv.end(), {"/usr/bin/fast-discovery-server", "-x",
                           "uavslam_discovery_server@" + spec_.qos_file});
  processes_.push_back(std::make_unique<process::ChildProcess>(argv, out("discovery_server.log")));
  if (!processes_.back()->started()) throw std::runtime_error("cannot start the discovery server");
}

OutageRecord TwoHostFlight::cut_link(EmulatedLink& link, double at_s,
                                     std::chrono::milliseconds length,
                                     const std::function<bool()>& stop) const {
  while (system_now() < start_at_ + at_s && !stop()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  OutageRecord r;
  r.lidar_before_kb = resident_kb(lidar_->pid());
  r.imu_before_kb = resident_kb(imu_->pid());
  link.outage(length);
  r.ended_at = system_now();
  r.lidar_after_kb = resident_kb(lidar_->pid());
  r.imu_after_kb = resident_kb(imu_->pid());
  return r;
}

FlightResult TwoHostFlight::finish(std::chrono::seconds timeout) {
  FlightResult r;
  r.start_at = start_at_;
  const auto grace = std::chrono::seconds(10);
  if (!lidar_->wait(timeout)) r.failure = "the LiDAR driver did not finish the flight";
  for (process::ChildProcess* p : {lidar_, imu_, matcher_, map_server_, station_}) {
    if (p && p->stop(grace) != 0 && r.failure.empty()) {
      r.failure = "a process failed: " + p->log();
    }
  }
  r.scans_published = count_before(lidar_->log(), "scans");
  r.scans_received = count_before(matcher_->log(), "scans received");
  r.scans_skipped = count_before(matcher_->log(), "skipped");
  r.poses_published = count_before(matcher_->log(), "poses published");
  if (fs::exists(out("gcs/summary.json"))) {
    std::ifstream in(out("gcs/summary.json"));
    r.station = nlohmann::json::parse(in);
    r.poses_at_station = r.station["poses"]["received"].get<long>();
  }
  r.pose_arrivals = read_arrivals(out("gcs/pose_arrivals.csv"));
  // A late-joining station has no trajectory to compare.
  if (fs::exists(out("gcs/trajectory.tum")) && fs::exists(out("groundtruth.tum"))) {
    const std::vector<Pose> poses = io::read_tum(out("gcs/trajectory.tum"));
    if (poses.size() >= 2) {
      r.errors = eval::compare_trajectories(poses, io::read_tum(out("groundtruth.tum")));
    }
  }
  return r;
}

}  // namespace uavslam::net
