// End-to-end latency on loopback: this program publishes a simulated flight's IMU samples and
// scans at their real rate (40 Hz scans) to a real `slam_matcher` process and receives its poses;
// the latency of a scan is the time from just before its write to the arrival of the pose made
// from it (one clock: this process's steady clock). It includes DDS delivery both ways, the
// matcher's queueing and the matching itself. Prints p50/p99/max; --json writes them too.
//
//   build/test/bench/bench_latency [--scenario config/scenarios/short.yaml] [--duration 20]
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>

#include <msg/ImuPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/ChildProcess.hpp"
#include "common/NodeOptions.hpp"
#include "common/RealTimePacer.hpp"
#include "common/StopRequest.hpp"
#include "core/Angles.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "eval/Percentile.hpp"
#include "io/ScenarioFile.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

struct Options {
  std::string scenario = std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/short.yaml";
  std::string slam_config = std::string(UAVSLAM_SOURCE_DIR) + "/config/slam.yaml";
  std::string matcher = std::string(UAVSLAM_BIN_DIR) + "/slam_matcher";
  double duration = 0.0;
  int domain = 187;
  int realtime_priority = 0;  // SCHED_FIFO for this program and the matcher; 0: normal
  std::string json;
};

// Publish times of scans by sequence, and the latency of each pose that came back.
class LatencyLog {
 public:
  void published(std::uint64_t seq) {
    std::lock_guard<std::mutex> lock(mutex_);
    sent_[seq] = Clock::now();
  }
  void pose_received(std::uint64_t scan_seq) {
    const auto now = Clock::now();
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = sent_.find(scan_seq);
    if (it == sent_.end()) return;
    latencies_ms_.push_back(std::chrono::duration<double, std::milli>(now - it->second).count());
  }
  void status_received(double processing_ms, double in_matcher_ms) {
    std::lock_guard<std::mutex> lock(mutex_);
    processing_ms_.push_back(processing_ms);
    in_matcher_ms_.push_back(in_matcher_ms);
  }
  std::vector<double> latencies_ms() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return latencies_ms_;
  }
  // The matcher's own figures: matching time, and scan publish to pose written.
  std::vector<double> processing_ms() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return processing_ms_;
  }
  std::vector<double> in_matcher_ms() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return in_matcher_ms_;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::uint64_t, Clock::time_point> sent_;
  std::vector<double> latencies_ms_;
  std::vector<double> processing_ms_;
  std::vector<double> in_matcher_ms_;
};

nlohmann::json to_json(const eval::SampleStats& s) {
  return {{"count", s.count},
          {"mean_ms", s.mean},
          {"p50_ms", s.p50},
          {"p99_ms", s.p99},
          {"max_ms", s.max}};
}

void print(const char* what, const eval::SampleStats& s) {
  std::cout << "  " << what << ": mean " << s.mean << " ms, p50 " << s.p50 << " ms, p99 " << s.p99
            << " ms, max " << s.max << " ms (" << s.count << ")\n";
}

// IMU samples and scans in stamp order at real time, each written as it falls due.
std::uint64_t fly(sim::FlightSimulator& simulator, const sim::Scenario& scenario, double duration,
                  dds::Writer<msg::LaserScanPubSubType>& scans,
                  dds::Writer<msg::ImuPubSubType>& imu, LatencyLog& log) {
  const double fov = deg_to_rad(scenario.lidar.fov_deg);
  const double increment = fov / (scenario.lidar.beams - 1);
  const double end = duration > 0 ? simulator.start_time() + duration : simulator.end_time();
  process::RealTimePacer pacer(1.0);
  Scan scan;
  ImuSample sample;
  bool have_scan = simulator.next_scan(scan), have_imu = simulator.next_imu(sample);
  std::uint64_t imu_seq = 0, published = 0;
  while ((have_scan || have_imu) && !process::stop_requested()) {
    if (have_imu && (!have_scan || sample.stamp <= scan.stamp)) {
      if (sample.stamp > end || !pacer.wait_until(sample.stamp)) break;
      imu.write(dds::to_msg(sample, imu_seq++, {"imu", "uav1"}));
      have_imu = simulator.next_imu(sample);
    } else {
      if (scan.stamp > end || !pacer.wait_until(scan.stamp)) break;
      const msg::LaserScan message = dds::to_msg(scan, -fov / 2.0, increment, {"laser", "uav1"});
      log.published(scan.sequence);
      scans.write(message);
      ++published;
      have_scan = simulator.next_scan(scan);
    }
  }
  return published;
}

int run(const Options& o) {
  process::enter_realtime(o.realtime_priority);
  const sim::Scenario scenario = io::load_scenario(o.scenario);
  sim::FlightSimulator simulator(scenario);
  dds::Participant participant(o.domain, dds::default_profiles_path(), "uavslam_loopback",
                               "bench_latency");
  LatencyLog log;
  dds::Writer<msg::LaserScanPubSubType> scans(participant, dds::topic_name("uav1", dds::kScanTopic),
                                              "sensor_writer");
  dds::Writer<msg::ImuPubSubType> imu(participant, dds::topic_name("uav1", dds::kImuTopic),
                                      "sensor_writer");
  dds::Reader<msg::PoseWithCovarianceStampedPubSubType> poses(
      participant, dds::topic_name("uav1", dds::kPoseTopic), "state_reader",
      [&](const msg::PoseWithCovarianceStamped& m, const eprosima::fastdds::dds::SampleInfo&) {
        log.pose_received(m.scan_seq());
      });
  dds::Reader<msg::MatcherStatusPubSubType> statuses(
      participant, dds::topic_name("uav1", dds::kMatcherStatusTopic), "status_reader",
      [&](const msg::MatcherStatus& m, const eprosima::fastdds::dds::SampleInfo&) {
        log.status_received(m.processing_ms(), m.latency_ms());
      });

  const fs::path matcher_log = fs::temp_directory_path() / "bench_latency_matcher.log";
  process::ChildProcess matcher(
      {o.matcher, "--domain", std::to_string(o.domain), "--vehicle", "uav1", "--sensor", o.scenario,
       "--slam-config", o.slam_config, "--realtime-priority", std::to_string(o.realtime_priority)},
      matcher_log.string());
  if (!scans.wait_for_matched(1, 30s) || !imu.wait_for_matched(1, 30s) ||
      !poses.wait_for_matched(1, 30s)) {
    std::cerr << "bench_latency: the matcher did not match within 30 s:\n" << matcher.log();
    return 1;
  }
  std::cerr << "bench_latency: flying " << scenario.name << " in real time...\n";
  const std::uint64_t published = fly(simulator, scenario, o.duration, scans, imu, log);
  poses.wait_for_received(published, 2s);  // the last poses are on their way
  matcher.stop(10s);
  std::filesystem::remove(matcher_log);

  const eval::SampleStats ms = eval::summarize(log.latencies_ms());
  const eval::SampleStats processing = eval::summarize(log.processing_ms());
  const eval::SampleStats in_matcher = eval::summarize(log.in_matcher_ms());
  std::cout << "bench_latency: " << scenario.name << ", " << published
            << " scans at 40 Hz over loopback, "
            << (o.realtime_priority > 0 ? "SCHED_FIFO " + std::to_string(o.realtime_priority)
                                        : std::string("normal scheduling"))
            << "\n";
  print("scan written -> pose received (end to end)", ms);
  print("scan written -> pose written (matcher's status)", in_matcher);
  print("matching alone (matcher's status)", processing);
  if (!o.json.empty()) {
    std::ofstream(o.json) << nlohmann::json{{"scans", published},
                                            {"end_to_end", to_json(ms)},
                                            {"in_matcher", to_json(in_matcher)},
                                            {"processing", to_json(processing)}}
                                 .dump(2)
                          << "\n";
  }
  return ms.count == 0 ? 1 : 0;
}

}  // namespace
}  // namespace uavslam

int main(int argc, char** argv) {
  uavslam::Options o;
  CLI::App app{"bench_latency: scan publish -> pose received, through a real slam_matcher process"};
  app.add_option("--scenario", o.scenario, "scenario YAML")->capture_default_str();
  app.add_option("--slam-config", o.slam_config, "SLAM parameters for the matcher")
      ->capture_default_str();
  app.add_option("--matcher", o.matcher, "the slam_matcher executable")->capture_default_str();
  app.add_option("--duration", o.duration, "seconds of the flight (0: all)")->capture_default_str();
  app.add_option("--domain", o.domain, "DDS domain id")->capture_default_str();
  app.add_option("--realtime-priority", o.realtime_priority,
                 "SCHED_FIFO priority for this program and the matcher (0: normal scheduling)")
      ->capture_default_str();
  app.add_option("--json", o.json, "also write the figures to this JSON file");
  CLI11_PARSE(app, argc, argv);
  uavslam::process::install_stop_handler();
  try {
    return uavslam::run(o);
  } catch (const std::exception& e) {
    std::cerr << "bench_latency: " << e.what() << "\n";
    return 1;
  }
}
