// One simulated flight of the real uavslam processes split across the two emulated hosts (or all
// on this host over loopback, the reference): the sensors always on the UAV, the matcher (and map
// server) on the UAV or on the ground, the ground station on the ground. Shared by the twohost
// tests and the link benchmark (bench_link), which assert on and print the same results.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "EmulatedLink.hpp"
#include "common/ChildProcess.hpp"
#include "eval/TrajectoryMetrics.hpp"

namespace uavslam::net {

struct FlightSpec {
  std::string bin_dir;   // where the uavslam processes are
  std::string scenario;  // the simulated flight (config/scenarios/*.yaml)
  std::string out_dir;   // logs and outputs, created if missing
  int domain = 0;
  double rate = 1.0;        // times real time
  double duration_s = 0.0;  // of the flight; 0: the whole scenario
  Host matcher_host = Host::kUav;
  bool map_server = true;
  bool discovery_server = false;  // a Fast DDS discovery server on the UAV, every process its
                                  // client (uavslam_link_*_client), instead of unicast peers
  std::string qos_file;           // the profiles the discovery server reads (-x profile@file)
  std::vector<std::string> matcher_flags;  // more slam_matcher flags
  bool station = true;                     // a ground station from the start
  bool station_latency = true;             // it subscribes scans to measure latency
};

struct FlightResult {
  long scans_published = -1;  // by the LiDAR driver
  long scans_received = -1;   // by the matcher
  long scans_skipped = -1;
  long poses_published = -1;  // by the matcher
  long poses_at_station = -1;
  double start_at = 0.0;              // the flight's start, system clock
  nlohmann::json station;             // the ground station's summary.json
  std::vector<double> pose_arrivals;  // system clock, from pose_arrivals.csv
  eval::TrajectoryErrors errors;      // the ground station's trajectory against the truth
  std::string failure;                // empty when every process ended cleanly

  // The share of published scans that got a pose.
  double matched_share() const;
  // Seconds from `t` (system clock) to the first pose at the ground station after it.
  std::optional<double> poses_resumed_after(double t) const;
};

// What an outage of the link in the middle of a flight did on the UAV: the sensors' resident
// memory (kB) before and after it, and when the link came back (system clock).
struct OutageRecord {
  double ended_at = 0.0;
  long lidar_before_kb = 0, lidar_after_kb = 0;
  long imu_before_kb = 0, imu_after_kb = 0;
};

class TwoHostFlight {
 public:
  // link: the two hosts; nullptr runs everything on this host with the loopback profile.
  TwoHostFlight(const FlightSpec& spec, const EmulatedLink* link);
  TwoHostFlight(const TwoHostFlight&) = delete;
  TwoHostFlight& operator=(const TwoHostFlight&) = delete;
  ~TwoHostFlight();

  // Starts the processes; the flight starts `lead_s` later on the system clock, once each
  // sensor has matched its subscribers.
  void start(double lead_s = 3.0);
  double start_at() const { return start_at_; }

  // Waits until `at_s` seconds into the flight (or until `stop` says so), then cuts `link` for
  // `length`, reading the sensors' memory on both sides of the outage.
  OutageRecord cut_link(
      EmulatedLink& link, double at_s, std::chrono::milliseconds length,
      const std::function<bool()>& stop = [] { return false; }) const;

  // Waits for the LiDAR driver to publish the flight's last scan and end.
  bool wait_for_sensors(std::chrono::seconds timeout) { return lidar_->wait(timeout); }

  // Waits for the LiDAR driver to finish the flight, then stops the rest (matcher, map server,
  // ground station) so they write their outputs, and gathers the results.
  FlightResult finish(std::chrono::seconds timeout);

  // Starts the uavslam process `name` on `host` with that host's participant profile (on this
  // host, the loopback one) and the flight's domain; owned and stopped by this flight.
  process::ChildProcess& launch(Host host, const std::string& name, std::vector<std::string> flags);
  std::string out(const std::string& name) const;

 private:
  std::vector<std::string> sensor_flags(int subscribers) const;
  void start_discovery_server();

  FlightSpec spec_;
  const EmulatedLink* link_;
  double start_at_ = 0.0;
  std::vector<std::unique_ptr<process::ChildProcess>> processes_;
  process::ChildProcess* station_ = nullptr;
  process::ChildProcess* map_server_ = nullptr;
  process::ChildProcess* matcher_ = nullptr;
  process::ChildProcess* imu_ = nullptr;
  process::ChildProcess* lidar_ = nullptr;
};

}  // namespace uavslam::net
