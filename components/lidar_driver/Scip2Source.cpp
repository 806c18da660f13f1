#include "lidar_driver/Scip2Source.hpp"

#include <iostream>
#include <limits>
#include <sstream>

#include "common/StopRequest.hpp"

namespace uavslam::lidar {
namespace {

using drivers::scip2::SensorConnection;

constexpr int kPollMs = 20;

// What the status line compares against the previous one.
struct StatusMark {
  double at = 0.0;
  std::uint64_t scans = 0;
};

void print_status(const SensorConnection& sensor, std::uint64_t published, StatusMark& mark,
                  double now) {
  const drivers::scip2::SessionCounts session = sensor.total_session_counts();
  const drivers::scip2::ReaderCounts reader = sensor.total_reader_counts();
  std::ostringstream line;
  line.precision(3);
  line << "lidar_driver: scip2 status: " << (session.scans - mark.scans) / (now - mark.at)
       << " scans/s, " << published << " published, " << session.dropped_scans << " dropped, "
       << reader.checksum_errors << " checksum errors, " << reader.garbage_bytes
       << " garbage bytes, " << session.damaged_scans << " damaged scans, "
       << sensor.counts().reconnects << " reconnects, sensor '" << sensor.session().sensor_status()
       << "', " << (sensor.connected() ? "connected" : "disconnected") << ", clock drift "
       << sensor.session().clock().drift_ppm() << " ppm\n";
  std::cerr << line.str();
  mark = {now, session.scans};
}

}  // namespace

msg::LaserScan to_scan_message(const drivers::scip2::TimedScan& timed,
                               const drivers::scip2::SensorDescription& sensor,
                               const drivers::scip2::ScanRequest& request, std::uint64_t seq,
                               const dds::Source& source) {
  Scan scan;
  scan.stamp = timed.host_stamp;
  scan.sequence = seq;
  scan.ranges.reserve(timed.data.distances_mm.size());
  for (const std::uint32_t mm : timed.data.distances_mm) {
    const bool measured = mm >= static_cast<std::uint32_t>(sensor.min_distance_mm) &&
                          mm <= static_cast<std::uint32_t>(sensor.max_distance_mm);
    scan.ranges.push_back(measured ? static_cast<float>(mm) * 1e-3f
                                   : std::numeric_limits<float>::infinity());
  }
  scan.intensities.assign(timed.data.intensities.begin(), timed.data.intensities.end());
  const double increment = sensor.angle_increment() * request.cluster;
  msg::LaserScan m = dds::to_msg(scan, sensor.angle_of_step(request.first_step), increment, source);
  m.range_min(static_cast<float>(sensor.min_distance_mm * 1e-3));
  m.range_max(static_cast<float>(sensor.max_distance_mm * 1e-3));
  m.scan_time(static_cast<float>(sensor.scan_period()));
  // A published beam spans `cluster` steps, as its angle does.
  m.time_increment(
      static_cast<float>(sensor.scan_period() * request.cluster / sensor.steps_per_turn));
  return m;
}

void stream_scip2_scans(const drivers::scip2::SensorAddress& address, const std::string& vehicle,
                        const Scip2SourceOptions& options,
                        const std::function<bool(const msg::LaserScan&)>& publish) {
  drivers::scip2::SessionOptions session;
  session.with_intensity = options.with_intensity;
  SensorConnection sensor(address, session);
  const dds::Source source{"laser", vehicle};
  std::uint64_t seq = 0;
  std::uint64_t published = 0;
  StatusMark mark{drivers::scip2::host_now(), 0};
  while (!process::stop_requested()) {
    sensor.poll(kPollMs);
    for (const std::string& event : sensor.take_events()) {
      std::cerr << "lidar_driver: scip2: " << event << "\n";
    }
    const auto& description = sensor.session().description();
    const auto& request = sensor.session().request();
    for (const drivers::scip2::TimedScan& scan : sensor.take_scans()) {
      if (!description || !request) continue;
      published += publish(to_scan_message(scan, *description, *request, seq++, source)) ? 1 : 0;
    }
    const double now = drivers::scip2::host_now();
    if (now - mark.at >= options.status_period_s) print_status(sensor, published, mark, now);
  }
  sensor.shut_down();
  print_status(sensor, published, mark, drivers::scip2::host_now());
  std::cerr << "lidar_driver: published " << published << " scans from " << address.text()
            << " (stopped)\n";
}

}  // namespace uavslam::lidar
