// bench_link: the figures of docs/deployment.md "Two hosts over WiFi" (`make bench-link`, needs
// root). Four real-time flights of the demo scenario with the real processes: all on this host over
// loopback (the reference), then across the emulated link (default 20 ms one way, 5 % loss each
// way, 20 Mbit/s) with the matcher on board, with the matcher on the ground, and with the matcher
// on the ground through a 2 s outage. Prints a markdown table and writes results.json.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "EmulatedLink.hpp"
#include "TwoHostFlight.hpp"
#include "common/StopRequest.hpp"

namespace uavslam::net {
namespace {

struct BenchOptions {
  std::string scenario = std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/demo.yaml";
  std::string out = "out/bench_link";
  double duration_s = 60.0;
  double delay_ms = 20.0;
  double loss = 0.05;
  double rate_mbit = 20.0;
  double outage_at_s = 30.0;
  double outage_s = 2.0;
  int domain = 226;
  bool discovery_server = false;
  std::string max_scan_backlog;  // empty: the matcher's default
  std::string slam_config;       // empty: the matcher's built-in defaults
};

// The link's bytes per topic from one side's traffic file, per second of flight.
nlohmann::json topic_rates(const std::string& file, double flight_s) {
  std::ifstream in(file);
  if (!in) return nlohmann::json::object();
  const nlohmann::json traffic = nlohmann::json::parse(in);
  nlohmann::json rates = nlohmann::json::object();
  for (const auto& [topic, t] : traffic["topics"].items()) {
    rates[topic] = t["bytes"].get<double>() / flight_s;
  }
  rates["total"] = traffic["total_bytes"].get<double>() / flight_s;
  return rates;
}

struct Run {
  std::string name;
  FlightResult result;
  nlohmann::json uav_to_gcs, gcs_to_uav;  // bytes/s per topic
  std::optional<double> recovery_s;       // poses at the station after the outage ended
  long uav_rss_growth_kb = 0;             // during the outage, summed over the sensors
};

class LinkBenchmark {
 public:
  explicit LinkBenchmark(const BenchOptions& o) : o_(o) {}

  Run fly(const std::string& name, bool over_link, Host matcher_host, bool outage) {
    std::cerr << "bench_link: " << name << " (" << o_.duration_s << " s of flight)\n";
    const std::string dir = o_.out + "/" + name;
    std::unique_ptr<EmulatedLink> link;
    if (over_link) {
      LinkSpec spec;
      spec.rate_mbit = o_.rate_mbit;
      spec.delay_ms = o_.delay_ms;
      spec.loss = o_.loss;
      spec.record_traffic = true;
      std::filesystem::create_directories(dir);
      link = std::make_unique<EmulatedLink>(spec, UAVSLAM_LINK_EMULATOR, dir);
    }
    FlightSpec spec;
    spec.bin_dir = UAVSLAM_BIN_DIR;
    spec.scenario = o_.scenario;
    spec.out_dir = dir;
    spec.domain = o_.domain + domain_offset_++;
    spec.duration_s = o_.duration_s;
    spec.matcher_host = matcher_host;
    spec.discovery_server = o_.discovery_server;
    spec.qos_file = std::string(UAVSLAM_SOURCE_DIR) + "/qos/uavslam_profiles.xml";
    if (!o_.max_scan_backlog.empty())
      spec.matcher_flags = {"--max-scan-backlog", o_.max_scan_backlog};
    Run run{name, {}, {}, {}, std::nullopt, 0};
    double outage_end = 0.0;
    {
      TwoHostFlight flight(spec, link.get());
      flight.start();
      if (outage && link) {
        const OutageRecord cut = flight.cut_link(
            *link, o_.outage_at_s, std::chrono::milliseconds(static_cast<long>(o_.outage_s * 1000)),
            [] { return process::stop_requested(); });
        outage_end = cut.ended_at;
        run.uav_rss_growth_kb =
            cut.lidar_after_kb + cut.imu_after_kb - cut.lidar_before_kb - cut.imu_before_kb;
      }
      // Ctrl-C ends the flight early; the processes still stop cleanly and write their outputs.
      const auto deadline =
          std::chrono::steady_clock::now() + std::chrono::duration<double>(o_.duration_s + 60);
      while (!flight.wait_for_sensors(std::chrono::seconds(1)) && !process::stop_requested() &&
             std::chrono::steady_clock::now() < deadline) {
      }
      run.result = flight.finish(std::chrono::seconds(0));
    }
    if (outage_end > 0.0) run.recovery_s = run.result.poses_resumed_after(outage_end);
    if (link) {
      link->stop_emulators();
      run.uav_to_gcs = topic_rates(link->traffic_file(Host::kUav), o_.duration_s);
      run.gcs_to_uav = topic_rates(link->traffic_file(Host::kGcs), o_.duration_s);
    }
    if (!run.result.failure.empty()) std::cerr << "bench_link: " << run.result.failure << "\n";
    return run;
  }

 private:
  BenchOptions o_;
  int domain_offset_ = 0;
};

std::string fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

double topic(const nlohmann::json& rates, const std::string& name) {
  return rates.contains(name) ? rates[name].get<double>() / 1000.0 : 0.0;
}

void print_table(const std::vector<Run>& runs, double reference_ate, const std::string& vehicle) {
  std::cout << "| run | scans matched | ATE (m) | ATE / loopback | pose latency p50 / p99 (ms) "
               "| poses resumed after the outage | link kB/s uav->gcs: scan, imu, pose, map, "
               "map_points, status, discovery, total | gcs->uav total |\n"
               "|---|---|---|---|---|---|---|---|\n";
  for (const Run& run : runs) {
    const FlightResult& r = run.result;
    const nlohmann::json& latency = r.station["latency_scan_to_pose"];
    std::cout << "| " << run.name << " | " << r.poses_published << " / " << r.scans_published
              << " (" << fixed(100.0 * r.matched_share(), 1) << " %) | "
              << fixed(r.errors.ate_horizontal_rmse, 4) << " | "
              << fixed(r.errors.ate_horizontal_rmse / reference_ate, 2) << " | "
              << fixed(latency.value("p50_ms", 0.0), 1) << " / "
              << fixed(latency.value("p99_ms", 0.0), 1) << " | "
              << (run.recovery_s ? fixed(*run.recovery_s * 1000.0, 0) + " ms (sensors' RSS " +
                                       std::to_string(run.uav_rss_growth_kb) + " kB)"
                                 : std::string("-"))
              << " | ";
    if (run.uav_to_gcs.empty()) {
      std::cout << "- | - |\n";
      continue;
    }
    for (const char* t : {"scan", "imu", "pose", "map", "map_points", "matcher_status"}) {
      std::cout << fixed(topic(run.uav_to_gcs, vehicle + "/" + t), 1) << ", ";
    }
    std::cout << fixed(topic(run.uav_to_gcs, "discovery"), 1) << ", "
              << fixed(topic(run.uav_to_gcs, "total"), 1) << " | "
              << fixed(topic(run.gcs_to_uav, "total"), 1) << " |\n";
  }
}

nlohmann::json to_json(const Run& run) {
  const FlightResult& r = run.result;
  return {{"run", run.name},
          {"scans_published", r.scans_published},
          {"poses_published", r.poses_published},
          {"poses_at_station", r.poses_at_station},
          {"matched_share", r.matched_share()},
          {"ate_horizontal_m", r.errors.ate_horizontal_rmse},
          {"latency_scan_to_pose", r.station.value("latency_scan_to_pose", nlohmann::json())},
          {"recovery_s", run.recovery_s ? nlohmann::json(*run.recovery_s) : nlohmann::json()},
          {"sensors_rss_growth_during_outage_kb", run.uav_rss_growth_kb},
          {"link_bytes_per_s_uav_to_gcs", run.uav_to_gcs},
          {"link_bytes_per_s_gcs_to_uav", run.gcs_to_uav},
          {"failure", r.failure}};
}

int run_benchmark(const BenchOptions& o) {
  const LinkAvailability can = EmulatedLink::available(UAVSLAM_LINK_EMULATOR);
  if (!can) {
    std::cerr << "bench_link: two hosts cannot be emulated here: " << can.reason << "\n";
    return 1;
  }
  LinkBenchmark bench(o);
  std::vector<Run> runs;
  runs.push_back(bench.fly("loopback", false, Host::kUav, false));
  runs.push_back(bench.fly("link_matcher_on_board", true, Host::kUav, false));
  runs.push_back(bench.fly("link_matcher_on_ground", true, Host::kGcs, false));
  runs.push_back(bench.fly("link_matcher_on_ground_outage", true, Host::kGcs, true));
  if (process::stop_requested()) {
    std::cerr << "bench_link: stopped by Ctrl-C; no table\n";
    return 130;
  }

  std::cout << "Link: " << o.delay_ms << " ms one way, " << 100.0 * o.loss << " % loss each way, "
            << o.rate_mbit << " Mbit/s; " << o.duration_s << " s of " << o.scenario
            << " in real time; outage " << o.outage_s << " s at " << o.outage_at_s << " s; "
            << (o.discovery_server ? "discovery server" : "unicast peer discovery")
            << (o.max_scan_backlog.empty() ? ""
                                           : "; matcher --max-scan-backlog " + o.max_scan_backlog)
            << "\n\n";
  print_table(runs, runs.front().result.errors.ate_horizontal_rmse, "uav1");
  nlohmann::json all = nlohmann::json::array();
  for (const Run& run : runs) all.push_back(to_json(run));
  std::ofstream(o.out + "/results.json") << all.dump(2) << "\n";
  std::cerr << "bench_link: wrote " << o.out << "/results.json\n";
  for (const Run& run : runs) {
    if (!run.result.failure.empty()) return 1;
  }
  return 0;
}

}  // namespace
}  // namespace uavslam::net

int main(int argc, char** argv) {
  CLI::App app{
      "bench_link: the system across an emulated WiFi link between two network namespaces "
      "(needs root): loopback reference, matcher on board, matcher on the ground, and an outage; "
      "share of scans matched, ATE against the loopback run, pose latency at the ground station, "
      "recovery after the outage, link bytes per topic"};
  uavslam::net::BenchOptions o;
  app.add_option("--scenario", o.scenario, "scenario YAML")->check(CLI::ExistingFile);
  app.add_option("--out", o.out, "directory for the runs' logs and results.json")
      ->capture_default_str();
  app.add_option("--duration", o.duration_s, "seconds of flight per run")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--delay-ms", o.delay_ms, "one-way delay")->capture_default_str();
  app.add_option("--loss", o.loss, "share lost each way")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.5));
  app.add_option("--rate-mbit", o.rate_mbit, "link rate")->capture_default_str();
  app.add_option("--outage-at", o.outage_at_s, "seconds into the flight")->capture_default_str();
  app.add_option("--outage", o.outage_s, "outage length, s")->capture_default_str();
  app.add_option("--domain", o.domain, "first DDS domain id (one per run)")
      ->capture_default_str()
      ->check(CLI::Range(0, 229));
  app.add_flag("--discovery-server", o.discovery_server,
               "discover through a Fast DDS discovery server on the UAV (uavslam_link_*_client "
               "profiles) instead of unicast initial peers");
  app.add_option("--max-scan-backlog", o.max_scan_backlog,
                 "passed to the matcher (0: keep only the newest scan, as before the backlog)");
  app.add_option("--slam-config", o.slam_config,
                 "SLAM parameters YAML for the matcher (e.g. one with `recovery: {gap: 0}`)")
      ->check(CLI::ExistingFile);
  CLI11_PARSE(app, argc, argv);
  uavslam::process::install_stop_handler();
  std::filesystem::create_directories(o.out);
  return uavslam::net::run_benchmark(o);
}
