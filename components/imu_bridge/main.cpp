// imu_bridge: publishes the `imu` topic. Source `sim`: the flight simulator's IMU along the same
// scenario (same seed) as the lidar_driver's, so the two agree on the flight; real time or
// `--rate` times faster.
#include <chrono>
#include <iostream>

#include <msg/ImuPubSubTypes.h>
#include <CLI/CLI.hpp>

#include "common/IncompatibleQos.hpp"
#include "common/NodeOptions.hpp"
#include "common/PacedStream.hpp"
#include "common/RunNode.hpp"
#include "common/SimSourceOptions.hpp"
#include "common/StopRequest.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "io/ScenarioFile.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam {
namespace {

int publish_imu(const process::NodeOptions& node, const process::SimSourceOptions& o) {
  const sim::Scenario scenario = io::load_scenario(o.scenario);
  sim::FlightSimulator simulator(scenario);

  dds::Participant participant(node.domain, process::profiles_path(node), node.participant_profile,
                               "imu_bridge");
  const std::string topic = dds::topic_name(node.vehicle, dds::kImuTopic);
  dds::Writer<msg::ImuPubSubType> writer(participant, topic,
                                         node.profile(dds::kImuTopic, "sensor_writer"));
  std::cerr << "imu_bridge: publishing " << topic << " from " << scenario.name << " at "
            << scenario.imu.rate_hz * o.rate << " Hz (domain " << node.domain << ")\n";

  if (!process::wait_for_subscribers(writer, o.wait_for_subscribers, "imu_bridge")) return 1;
  const dds::Source source{"imu", node.vehicle};
  std::uint64_t seq = 0;
  process::QosWatch qos("imu_bridge");
  const process::StreamCounts counts = process::publish_paced<ImuSample>(
      o, simulator.start_time(), [&](ImuSample& sample) { return simulator.next_imu(sample); },
      [&](const ImuSample& sample) {
        qos.output(writer);
        return writer.write(dds::to_msg(sample, seq++, source));
      });
  std::cerr << "imu_bridge: published " << counts.published << " samples, " << counts.missed
            << " overdue and skipped" << (process::stop_requested() ? " (stopped)" : "") << "\n";
  return qos.exit_code();
}

}  // namespace
}  // namespace uavslam

int main(int argc, char** argv) {
  CLI::App app{"imu_bridge: publishes the `imu` topic (source sim: the flight simulator)"};
  uavslam::process::NodeOptions node;
  uavslam::process::SimSourceOptions source;
  uavslam::process::add_node_options(app, node);
  uavslam::process::add_sim_source_options(app, source);
  if (const auto code = uavslam::process::parse_command_line(app, argc, argv)) return *code;
  uavslam::process::install_stop_handler();
  return uavslam::process::run_node("imu_bridge", [&] {
    if (const auto section = uavslam::process::apply_node_config(app, node, "imu_bridge")) {
      uavslam::process::apply_sim_source_config(app, *section, source);
    }
    return uavslam::publish_imu(node, source);
  });
}
