// imu_bridge: publishes the `imu` topic. Source `sim`: the flight simulator's IMU along the same
// scenario (same seed) as the lidar_driver's, so the two agree on the flight, and the autopilot's
// `velocity` when the scenario's vehicle has a velocity source; real time or `--rate` times
// faster. Source `carmen:FILE`: the robots of CARMEN logs had no IMU, their wheel
// odometry is their only rotation sensor (and it drifts): one orientation sample per laser scan,
// at the scan's timeline stamp, the yaw of the laser pose's odometry heading, published a little
// ahead of the lidar_driver's scan on the shared --start-at timeline (CarmenReplay.hpp); and the
// laser pose itself (x, y, heading) as `odom` at the same stamp, for a matcher whose SLAM config
// takes the odometry as its motion prior. The laser's, not the robot's: over DDS the scan's frame
// is the laser (the scan message carries no mount). Source `mcap:FILE`: the `imu` (or
// `VEHICLE/imu`) channel of an MCAP recording, as recorded, at its log_time spacing (or `--rate`
// times faster) on the file's timeline, which the lidar_driver replaying the same file shares.
// Source `mavlink:udp:PORT` / `mavlink:serial:DEVICE:BAUD`: a real autopilot (MavlinkSource.hpp).
#include <chrono>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <variant>

#include <msg/ImuPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <msg/TwistPubSubTypes.h>
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
#include "imu_bridge/MavlinkSource.hpp"
#include "io/CarmenSamples.hpp"
#include "io/CarmenScanStream.hpp"
#include "io/ScenarioFile.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam {
namespace {

// One sample of the simulated autopilot, in stamp order: an IMU sample or, when the scenario has
// a velocity source, a velocity (at equal stamps the IMU's first).
struct AutopilotSample {
  double stamp = 0.0;
  std::variant<ImuSample, VelocitySample> data;
};

class AutopilotStream {
 public:
  explicit AutopilotStream(sim::FlightSimulator& simulator) : simulator_(simulator) {
    has_imu_ = simulator_.next_imu(imu_);
    has_velocity_ = simulator_.next_velocity(velocity_);
  }

  bool next(AutopilotSample& out) {
    if (has_imu_ && (!has_velocity_ || imu_.stamp <= velocity_.stamp)) {
      out = {imu_.stamp, imu_};
      has_imu_ = simulator_.next_imu(imu_);
      return true;
    }
    if (!has_velocity_) return false;
    out = {velocity_.stamp, velocity_};
    has_velocity_ = simulator_.next_velocity(velocity_);
    return true;
  }

 private:
  sim::FlightSimulator& simulator_;
  ImuSample imu_;
  VelocitySample velocity_;
  bool has_imu_ = false;
  bool has_velocity_ = false;
};

int publish_imu(const process::NodeOptions& node, const process::SimSourceOptions& o) {
  const sim::Scenario scenario = io::load_scenario(o.scenario);
  sim::FlightSimulator simulator(scenario);

  dds::Participant participant(node.domain, process::profiles_path(node), node.participant_profile,
                               "imu_bridge");
  const std::string topic = dds::topic_name(node.vehicle, dds::kImuTopic);
  // The autopilot's velocity when the scenario's vehicle has one. --wait-for-subscribers counts imu
  // readers only: a matcher reads velocity only when its config fuses it, and creates that reader
  // before its imu reader (a participant announces them in that order).
  std::optional<dds::Writer<msg::TwistWithCovarianceStampedPubSubType>> velocity;
  if (scenario.velocity.rate_hz > 0.0) {
    velocity.emplace(participant, dds::topic_name(node.vehicle, dds::kVelocityTopic),
                     node.profile(dds::kVelocityTopic, "sensor_writer"));
  }
  dds::Writer<msg::ImuPubSubType> writer(participant, topic,
                                         node.profile(dds::kImuTopic, "sensor_writer"));
  std::cerr << "imu_bridge: publishing " << topic << " from " << scenario.name << " at "
            << scenario.imu.rate_hz * o.rate << " Hz";
  if (velocity) {
    std::cerr << " and " << velocity->topic() << " at " << scenario.velocity.rate_hz * o.rate
              << " Hz";
  }
  std::cerr << " (domain " << node.domain << ")\n";

  if (!process::wait_for_subscribers(writer, o.wait_for_subscribers, "imu_bridge")) return 1;
  std::uint64_t seq = 0;
  std::uint64_t velocity_seq = 0;
  const dds::Source velocity_source{"imu", node.vehicle};
  process::QosWatch qos("imu_bridge");
  AutopilotStream stream(simulator);
  const process::StreamCounts counts = process::publish_paced<AutopilotSample>(
      o, simulator.start_time(), [&](AutopilotSample& sample) { return stream.next(sample); },
      [&](const AutopilotSample& sample) {
        qos.output(writer);
        if (const auto* imu = std::get_if<ImuSample>(&sample.data)) {
          return writer.write(dds::simulated_imu_message(*imu, seq++, node.vehicle));
        }
        qos.output(*velocity);
        return velocity->write(
            dds::to_msg(std::get<VelocitySample>(sample.data), velocity_seq++, velocity_source));
      });
  std::cerr << "imu_bridge: published " << counts.published << " samples";
  if (velocity) std::cerr << " (" << velocity_seq << " of them velocities)";
  std::cerr << ", " << counts.missed << " overdue and skipped"
            << (process::stop_requested() ? " (stopped)" : "") << "\n";
  process::give_readers_the_last_samples();
  return qos.exit_code();
}

// The odometry pose, planar: the motion prior's source (`odom`).
Pose odometry_pose(const io::CarmenSamples& samples) {
  return {samples.odometry.stamp, samples.odometry.position, samples.orientation.orientation};
}

int replay_odometry(const process::NodeOptions& node, const process::SimSourceOptions& o,
                    const std::string& log_path) {
  io::CarmenScanStream stream(log_path, o.max_scans);  // a missing file: FileError, exit 2
  dds::Participant participant(node.domain, process::profiles_path(node), node.participant_profile,
                               "imu_bridge");
  const std::string topic = dds::topic_name(node.vehicle, dds::kImuTopic);
  // --wait-for-subscribers counts imu readers only: a matcher reads odom only when its config asks
  // for the odometry prior. It creates its odom reader before its imu reader, and a participant
  // announces its readers in that order, so its odom reader has matched by then too.
  dds::Writer<msg::PoseWithCovarianceStampedPubSubType> odometry(
      participant, dds::topic_name(node.vehicle, dds::kOdometryTopic),
      node.profile(dds::kOdometryTopic, "sensor_writer"));
  dds::Writer<msg::ImuPubSubType> writer(participant, topic,
                                         node.profile(dds::kImuTopic, "sensor_writer"));
  const double lead = process::orientation_lead(o.rate);
  std::cerr << "imu_bridge: publishing " << topic << " and " << odometry.topic()
            << " from the odometry of " << log_path << " at " << o.rate << "x the recorded rate, "
            << lead * 1e3 << " ms ahead of the scans (domain " << node.domain << ")\n";

  if (!process::wait_for_subscribers(writer, o.wait_for_subscribers, "imu_bridge")) return 1;
  // The scans go out as LaserScan messages, which carry no mount: the laser is the body.
  io::CarmenSensor sensor(io::CarmenBody::Laser);
  const dds::Source imu_source{"imu", node.vehicle};
  const dds::Source odometry_source{"odom", node.vehicle};
  process::QosWatch qos("imu_bridge");
  std::uint64_t odometry_published = 0;
  const process::ReplayCounts counts = process::replay_carmen_scans(
      o, stream, lead, "imu_bridge", [&](const io::TimedCarmenScan& scan) {
        const io::CarmenSamples samples = sensor.samples_of(scan);
        qos.output(writer);
        qos.output(odometry);
        odometry_published += odometry.write(
            dds::to_msg(odometry_pose(samples), 1.0f, scan.index, scan.index, odometry_source));
        return writer.write(dds::to_msg(samples.orientation, scan.index, imu_source));
      });
  std::cerr << "imu_bridge: published " << counts.published << " odometry headings and "
            << odometry_published << " odometry poses of " << log_path << ", "
            << stream.malformed_lines() << " malformed lines skipped, " << counts.late
            << " published late (> 0.25 s)" << (process::stop_requested() ? " (stopped)" : "")
            << "\n";
  process::give_readers_the_last_samples();
  return qos.exit_code();
}

// The recording's `imu` channel; with --max-scans its scans are read too, to end where the
// lidar_driver's replay of the same file ends.
std::set<std::string> recorded_imu_topics(const process::NodeOptions& node,
                                          const process::SimSourceOptions& o) {
  std::set<std::string> topics = process::recorded_topics(node.vehicle, dds::kImuTopic);
  const std::set<std::string> velocity =
      process::recorded_topics(node.vehicle, dds::kVelocityTopic);
  topics.insert(velocity.begin(), velocity.end());
  if (o.max_scans > 0) {
    const std::set<std::string> scans = process::recorded_topics(node.vehicle, dds::kScanTopic);
    topics.insert(scans.begin(), scans.end());
  }
  return topics;
}

int replay_recorded_imu(const process::NodeOptions& node, const process::SimSourceOptions& o,
                        const std::string& log_path) {
  // A missing, foreign or unreadable file: FileError naming it, exit 2.
  dds::RecordedMessageStream stream(log_path, recorded_imu_topics(node, o));
  dds::Participant participant(node.domain, process::profiles_path(node), node.participant_profile,
                               "imu_bridge");
  const std::string topic = dds::topic_name(node.vehicle, dds::kImuTopic);
  // The autopilot's velocity, where the recording has it; created before the imu writer, as the
  // matcher creates its reader (--wait-for-subscribers counts imu readers).
  dds::Writer<msg::TwistWithCovarianceStampedPubSubType> velocity(
      participant, dds::topic_name(node.vehicle, dds::kVelocityTopic),
      node.profile(dds::kVelocityTopic, "sensor_writer"));
  dds::Writer<msg::ImuPubSubType> writer(participant, topic,
                                         node.profile(dds::kImuTopic, "sensor_writer"));
  std::cerr << "imu_bridge: publishing " << topic << " (and " << velocity.topic()
            << " where recorded) from " << log_path << " at " << o.rate
            << "x the recorded rate (domain " << node.domain << ")\n";
  return process::replay_recording<msg::Imu>(
      o, stream, writer, "imu", "samples", "imu_bridge", [&](const dds::RecordedMessage& message) {
        const auto* sample = std::get_if<msg::TwistWithCovarianceStamped>(&message.sample);
        return sample && velocity.write(*sample);
      });
}

int publish(const process::NodeOptions& node, const process::SimSourceOptions& o,
            const process::MavlinkOptions& mavlink) {
  if (process::is_mavlink_source(o.source)) return process::bridge_autopilot(node, o, mavlink);
  if (const std::optional<std::string> log_path = process::carmen_log_path(o)) {
    return replay_odometry(node, o, *log_path);
  }
  if (const std::optional<std::string> log_path = process::mcap_log_path(o)) {
    return replay_recorded_imu(node, o, *log_path);
  }
  return publish_imu(node, o);
}

}  // namespace
}  // namespace uavslam

int main(int argc, char** argv) {
  CLI::App app{
      "imu_bridge: publishes the `imu` topic (source sim: the flight simulator; source "
      "carmen:FILE: the odometry heading of each laser scan of a CARMEN log as its orientation, "
      "and the laser's odometry pose as the `odom` topic at the same stamp; source mcap:FILE: "
      "the `imu` channel of an MCAP recording, at its log_time spacing; source "
      "mavlink:udp:PORT or mavlink:serial:DEVICE:BAUD: a PX4/ArduPilot autopilot's attitude "
      "and IMU, with the `pose` topic sent back to it as external vision)"};
  uavslam::process::NodeOptions node;
  uavslam::process::SimSourceOptions source;
  source.device_prefixes = {"mavlink:"};
  uavslam::process::add_node_options(app, node);
  uavslam::process::add_sim_source_options(app, source);
  uavslam::process::MavlinkOptions mavlink;
  uavslam::process::add_mavlink_options(app, mavlink);
  if (const auto code = uavslam::process::parse_command_line(app, argc, argv)) return *code;
  uavslam::process::install_stop_handler();
  return uavslam::process::run_node("imu_bridge", [&] {
    if (const auto section = uavslam::process::apply_node_config(app, node, "imu_bridge")) {
      uavslam::process::apply_sim_source_config(app, *section, source,
                                                uavslam::process::mavlink_config_keys());
      uavslam::process::apply_mavlink_config(app, *section, mavlink);
    }
    return uavslam::publish(node, source, mavlink);
  });
}
