#include "SimulatedFlight.hpp"

#include <chrono>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <msg/ImuPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <msg/TwistPubSubTypes.h>

#include "common/StopRequest.hpp"
#include "dds/Conversions.hpp"
#include "dds/McapChannels.hpp"
#include "dds/RecordedMessages.hpp"
#include "dds/SimulatedSensorMessages.hpp"
#include "dds/Topics.hpp"
#include "io/McapWriter.hpp"
#include "sim/FlightSimulator.hpp"
#include "slam/VehicleSlam.hpp"

namespace uavslam::cli {

SensorLog simulate_sensors(const sim::Scenario& scenario) {
  sim::FlightSimulator simulator(scenario);
  SensorLog log;
  log.duration = simulator.end_time() - simulator.start_time();
  ImuSample imu;
  while (simulator.next_imu(imu)) log.imu.push_back(imu);
  VelocitySample velocity;
  while (simulator.next_velocity(velocity)) log.velocity.push_back(velocity);
  Scan scan;
  while (simulator.next_scan(scan)) {
    log.ground_truth.push_back(simulator.ground_truth_at(scan.stamp));
    log.scans.push_back(std::move(scan));
  }
  return log;
}

namespace {

// One channel of the recording with its message count (the MCAP sequence number).
template <typename PubSubType>
class RecordedChannel {
 public:
  RecordedChannel(io::McapWriter& writer, const std::string& topic)
      : writer_(writer), id_(dds::add_dds_channel(writer, topic, dds::schema_name<PubSubType>())) {}

  void write(double stamp, const typename PubSubType::type& sample) {
    const std::vector<std::uint8_t> bytes = dds::to_cdr<PubSubType>(sample);
    const std::uint64_t time = dds::to_mcap_time(stamp);
    writer_.write(id_, sequence_++, time, time, bytes.data(), bytes.size());
  }

 private:
  io::McapWriter& writer_;
  std::uint16_t id_;
  std::uint32_t sequence_ = 0;
};

}  // namespace

void write_flight_log(const std::string& path, const sim::Scenario& scenario,
                      const SensorLog& log) {
  io::McapWriter writer(path);
  RecordedChannel<msg::LaserScanPubSubType> scans(writer, dds::kScanTopic);
  RecordedChannel<msg::ImuPubSubType> imu(writer, dds::kImuTopic);
  RecordedChannel<msg::PoseWithCovarianceStampedPubSubType> truth(writer, dds::kGroundTruthTopic);
  std::optional<RecordedChannel<msg::TwistWithCovarianceStampedPubSubType>> velocity;
  if (!log.velocity.empty()) velocity.emplace(writer, dds::kVelocityTopic);
  std::size_t next_imu = 0;
  std::size_t next_velocity = 0;
  const auto write_imu_up_to = [&](double stamp) {
    for (; next_imu < log.imu.size() && log.imu[next_imu].stamp <= stamp; ++next_imu) {
      imu.write(log.imu[next_imu].stamp,
                dds::simulated_imu_message(log.imu[next_imu], next_imu, ""));
    }
    for (; next_velocity < log.velocity.size() && log.velocity[next_velocity].stamp <= stamp;
         ++next_velocity) {
      const VelocitySample& v = log.velocity[next_velocity];
      velocity->write(v.stamp, dds::to_msg(v, next_velocity, {"imu", ""}));
    }
  };
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    const Scan& scan = log.scans[i];
    write_imu_up_to(scan.stamp);
    truth.write(scan.stamp, dds::ground_truth_message(log.ground_truth[i], scan.sequence, i, ""));
    scans.write(scan.stamp, dds::simulated_scan_message(scan, scenario.lidar, ""));
  }
  write_imu_up_to(std::numeric_limits<double>::infinity());
  writer.close();
}

SlamRun run_slam(const SensorLog& log, const SlamConfig& config,
                 const std::function<void(std::size_t, std::size_t)>& progress) {
  using Clock = std::chrono::steady_clock;
  SlamRun run;
  if (log.scans.empty()) return run;
  // The vehicle starts where the flight starts: the estimate and the truth share a frame.
  VehicleSlam slam(config);
  slam.start_at(log.ground_truth.front().position);
  std::size_t next_imu = 0;
  std::size_t next_velocity = 0;
  std::vector<std::optional<ScanAnchor>> anchors;  // one per accepted scan
  const auto run_start = Clock::now();
  for (std::size_t i = 0; i < log.scans.size(); ++i) {
    if (process::stop_requested()) {
      run.stopped_early = true;
      break;
    }
    const Scan& scan = log.scans[i];
    // Every IMU sample up to the scan's stamp arrives before the scan, as on the vehicle.
    for (; next_imu < log.imu.size() && log.imu[next_imu].stamp <= scan.stamp; ++next_imu) {
      slam.add_imu(log.imu[next_imu]);
    }
    for (; next_velocity < log.velocity.size() && log.velocity[next_velocity].stamp <= scan.stamp;
         ++next_velocity) {
      slam.add_velocity(log.velocity[next_velocity]);
    }
    const VehicleScan result = slam.process_scan(scan);
    const ScanReport& report = result.report;
    run.scan_seconds.push_back(result.pipeline_seconds);
    ++run.scans_in;
    const Vec3& truth = log.ground_truth[i].position;
    const std::optional<eval::Nees> nees =
        eval::nees(report.pose.position - truth, report.absolute_covariance());
    if (report.accepted()) {
      run.estimate.push_back(report.pose);
      anchors.push_back(result.anchor);
      run.ground_truth.push_back(log.ground_truth[i]);
      if (nees) run.nees.push_back(*nees);
      if (report.prior_distance > 0.0) run.prior_distances.push_back(report.prior_distance);
    }
    if (report.frame_turn) {
      run.heading_anchor =
          SlamRun::AnchorTurn{report.frame_turn->yaw, scan.stamp - log.scans.front().stamp};
    }
    run.tracking.add(result.tracking);
    run.trace.push_back({scan.stamp,
                         report.outcome,
                         report.points_used,
                         report.error_before,
                         report.error_after,
                         report.iterations,
                         report.map_updated,
                         report.pose.position,
                         truth,
                         run.scan_seconds.back() * 1e3,
                         report.seen.degenerate,
                         report.seen.weakest_fraction,
                         report.absolute_covariance().diagonal().cwiseSqrt(),
                         report.prior_distance,
                         result.tracking,
                         report.floor_returns,
                         report.height_from_floor,
                         nees,
                         report.blind_fixed,
                         report.moving_points});
    if (progress && i % 400 == 0) progress(i, log.scans.size());
  }
  if (slam.finish()) {
    for (std::size_t k = 0; k < run.estimate.size(); ++k) {
      run.smoothed.push_back(anchors[k] ? slam.smoothed(run.estimate[k], *anchors[k])
                                        : run.estimate[k]);
    }
  }
  run.loops = slam.loops();
  run.backend_seconds = slam.backend_seconds();
  run.wall_seconds = std::chrono::duration<double>(Clock::now() - run_start).count();
  run.outcomes = slam.pipeline().outcome_counts();
  run.map = slam.pipeline().map().points();
  run.keyframes = slam.keyframes();
  run.heading_drift = slam.pipeline().heading_drift();
  if (progress) progress(run.scans_in, log.scans.size());
  return run;
}

}  // namespace uavslam::cli
