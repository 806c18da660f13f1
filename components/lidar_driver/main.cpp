// lidar_driver: publishes the `scan` topic. Source `sim`: the flight simulator's LiDAR along a
// scenario's flight, in real time or `--rate` times faster; `--groundtruth FILE` also writes the
// simulator's true pose at every published scan (TUM), for evaluating the run afterwards.
// Source `carmen:FILE`: every laser scan of a CARMEN log, in file order, at the recorded pace (or
// `--rate` times faster), stamped on the log's timeline (io/CarmenTimeline.hpp).
// Source `mcap:FILE`: the `scan` (or `VEHICLE/scan`) channel of an MCAP recording, each message as
// it was recorded, at its log_time spacing (or `--rate` times faster; McapReplay.hpp).
// Source `scip2:DEVICE` / `scip2tcp:HOST:PORT`: a Hokuyo over SCIP 2.0, live (Scip2Source.hpp).
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <variant>

#include <msg/LaserScanPubSubTypes.h>
#include <CLI/CLI.hpp>

#include "common/CarmenReplay.hpp"
#include "common/IncompatibleQos.hpp"
#include "common/McapReplay.hpp"
#include "common/NodeOptions.hpp"
#include "common/PacedStream.hpp"
#include "common/ReaderGrace.hpp"
#include "common/RunNode.hpp"
#include "common/SimSourceOptions.hpp"
#include "common/StopRequest.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/RecordedMessageStream.hpp"
#include "dds/SimulatedSensorMessages.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "io/CarmenSamples.hpp"
#include "io/CarmenScanStream.hpp"
#include "io/ScenarioFile.hpp"
#include "io/TumFile.hpp"
#include "lidar_driver/Scip2Source.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam {
namespace {

std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// The `scan` writer every source publishes through, announced on stderr.
struct ScanOutput {
  ScanOutput(const process::NodeOptions& node, const std::string& from, const std::string& pace)
      : participant(node.domain, process::profiles_path(node), node.participant_profile,
                    "lidar_driver"),
        topic(dds::topic_name(node.vehicle, dds::kScanTopic)),
        writer(participant, topic, node.profile(dds::kScanTopic, "sensor_writer")) {
    std::cerr << "lidar_driver: publishing " << topic << " from " << from << " at " << pace
              << " (domain " << node.domain << ")\n";
  }
  dds::Participant participant;
  std::string topic;
  dds::Writer<msg::LaserScanPubSubType> writer;
};

int publish_scans(const process::NodeOptions& node, const process::SimSourceOptions& o,
                  const std::string& groundtruth_path) {
  const sim::Scenario scenario = io::load_scenario(o.scenario);
  sim::FlightSimulator simulator(scenario);

  ScanOutput out(node, scenario.name, number_text(scenario.lidar.rate_hz * o.rate) + " Hz");
  auto& writer = out.writer;

  if (!process::wait_for_subscribers(writer, o.wait_for_subscribers, "lidar_driver")) return 1;
  std::vector<Pose> truth;
  process::QosWatch qos("lidar_driver");
  const process::StreamCounts counts = process::publish_paced<Scan>(
      o, simulator.start_time(), [&](Scan& scan) { return simulator.next_scan(scan); },
      [&](const Scan& scan) {
        qos.output(writer);
        if (!groundtruth_path.empty()) truth.push_back(simulator.ground_truth_at(scan.stamp));
        return writer.write(dds::simulated_scan_message(scan, scenario.lidar, node.vehicle));
      });
  if (!groundtruth_path.empty()) io::write_tum(groundtruth_path, truth);
  std::cerr << "lidar_driver: published " << counts.published << " scans, " << counts.missed
            << " overdue and skipped" << (process::stop_requested() ? " (stopped)" : "") << "\n";
  process::give_readers_the_last_samples();
  return qos.exit_code();
}

// The scan of a CARMEN log as published: sensor_msgs/LaserScan's beam layout is the log's, and it
// carries no mount, so the laser is the body (as imu_bridge --source carmen:FILE publishes it).
msg::LaserScan to_msg(io::CarmenSensor& sensor, const io::TimedCarmenScan& timed,
                      const dds::Source& source) {
  const Scan scan = sensor.samples_of(timed).scan;
  return dds::to_msg(scan, timed.scan.start_angle, timed.scan.angle_increment, source);
}

int replay_scans(const process::NodeOptions& node, const process::SimSourceOptions& o,
                 const std::string& log_path) {
  io::CarmenScanStream stream(log_path, o.max_scans);  // a missing file: FileError, exit 2
  ScanOutput out(node, log_path, number_text(o.rate) + "x the recorded rate");
  auto& writer = out.writer;

  if (!process::wait_for_subscribers(writer, o.wait_for_subscribers, "lidar_driver")) return 1;
  const dds::Source source{"laser", node.vehicle};
  io::CarmenSensor sensor(io::CarmenBody::Laser);
  process::QosWatch qos("lidar_driver");
  const process::ReplayCounts counts = process::replay_carmen_scans(
      o, stream, 0.0, "lidar_driver", [&](const io::TimedCarmenScan& scan) {
        qos.output(writer);
        return writer.write(to_msg(sensor, scan, source));
      });
  std::cerr << "lidar_driver: published " << counts.published << " scans of " << log_path << ", "
            << stream.malformed_lines() << " malformed lines skipped, " << counts.late
            << " published late (> 0.25 s)" << (process::stop_requested() ? " (stopped)" : "")
            << "\n";
  process::give_readers_the_last_samples();
  return qos.exit_code();
}

int replay_recorded_scans(const process::NodeOptions& node, const process::SimSourceOptions& o,
                          const std::string& log_path) {
  // A missing, foreign or unreadable file: FileError naming it, exit 2.
  dds::RecordedMessageStream stream(log_path,
                                    process::recorded_topics(node.vehicle, dds::kScanTopic));
  ScanOutput out(node, log_path, number_text(o.rate) + "x the recorded rate");
  return process::replay_recording<msg::LaserScan>(o, stream, out.writer, "scan", "scans",
                                                   "lidar_driver");
}

int stream_from_sensor(const process::NodeOptions& node, const process::SimSourceOptions& o,
                       const drivers::scip2::SensorAddress& address,
                       const lidar::Scip2SourceOptions& scip2) {
  ScanOutput out(node, "the Hokuyo at " + address.text(), "the sensor's rate");
  if (!process::wait_for_subscribers(out.writer, o.wait_for_subscribers, "lidar_driver")) return 1;
  process::QosWatch qos("lidar_driver");
  lidar::stream_scip2_scans(address, node.vehicle, scip2, [&](const msg::LaserScan& scan) {
    qos.output(out.writer);
    return out.writer.write(scan);
  });
  process::give_readers_the_last_samples();
  return qos.exit_code();
}

int publish(const process::NodeOptions& node, const process::SimSourceOptions& o,
            const std::string& groundtruth_path, const lidar::Scip2SourceOptions& scip2) {
  std::string problem;
  const auto sensor = drivers::scip2::parse_sensor_address(o.source, problem);
  if (!problem.empty()) {
    std::cerr << "lidar_driver: --source: " << problem << "\n";
    return 2;
  }
  if (sensor && !groundtruth_path.empty()) {
    std::cerr << "lidar_driver: --groundtruth needs --source sim\n";
    return 2;
  }
  if (sensor) return stream_from_sensor(node, o, *sensor, scip2);
  const std::optional<std::string> carmen = process::carmen_log_path(o);
  const std::optional<std::string> mcap = process::mcap_log_path(o);
  if (!carmen && !mcap) return publish_scans(node, o, groundtruth_path);
  if (!groundtruth_path.empty()) {
    std::cerr << "lidar_driver: --groundtruth needs --source sim (a log's ground truth is its "
                 "own)\n";
    return 2;
  }
  return carmen ? replay_scans(node, o, *carmen) : replay_recorded_scans(node, o, *mcap);
}

}  // namespace
}  // namespace uavslam

int main(int argc, char** argv) {
  CLI::App app{
      "lidar_driver: publishes the `scan` topic (source sim: the flight simulator; source "
      "carmen:FILE: the laser scans of a CARMEN log, replayed at the recorded pace; source "
      "mcap:FILE: the `scan` channel of an MCAP recording, at its log_time spacing; source "
      "scip2:DEVICE or scip2tcp:HOST:PORT: a Hokuyo laser scanner over SCIP 2.0)"};
  uavslam::process::NodeOptions node;
  uavslam::process::SimSourceOptions source;
  source.device_prefixes = {"scip2:", "scip2tcp:"};
  uavslam::process::add_node_options(app, node);
  uavslam::process::add_sim_source_options(app, source);
  std::string groundtruth;
  app.add_option("--groundtruth", groundtruth,
                 "sim: also write the simulator's true pose at each published scan to this TUM "
                 "file");
  uavslam::lidar::Scip2SourceOptions scip2;
  app.add_option("--status-period", scip2.status_period_s,
                 "scip2, scip2tcp: seconds between status lines on stderr")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  if (const auto code = uavslam::process::parse_command_line(app, argc, argv)) return *code;
  uavslam::process::install_stop_handler();
  return uavslam::process::run_node("lidar_driver", [&] {
    if (const auto section = uavslam::process::apply_node_config(app, node, "lidar_driver")) {
      uavslam::process::apply_sim_source_config(app, *section, source,
                                                {"groundtruth", "status_period"});
      if (uavslam::process::unset(app, "--groundtruth")) {
        groundtruth = section->get_string_or("groundtruth", groundtruth);
      }
      if (uavslam::process::unset(app, "--status-period")) {
        scip2.status_period_s = section->get_double_or("status_period", scip2.status_period_s);
      }
    }
    return uavslam::publish(node, source, groundtruth, scip2);
  });
}
