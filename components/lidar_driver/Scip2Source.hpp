// lidar_driver's `scip2:DEVICE` / `scip2tcp:HOST:PORT` source: a Hokuyo speaking SCIP 2.0
// (src/drivers/scip2), its scans published as `scan` messages stamped on the host's system clock,
// with a status line on stderr every few seconds (scan rate, dropped scans, checksum errors,
// garbage bytes, reconnects, the sensor's own status). Runs until Ctrl-C/SIGTERM; a sensor that
// goes away is reconnected, never the process restarted.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include <msg/LaserScan.h>

#include "dds/Conversions.hpp"
#include "drivers/scip2/SensorConnection.hpp"

namespace uavslam::lidar {

struct Scip2SourceOptions {
  double status_period_s = 5.0;
  bool with_intensity = true;  // ME; MD when the sensor refuses it
};

// The `scan` message of one scan: ranges in metres (values outside the sensor's DMIN..DMAX, its
// error codes among them, read as +inf: no return), beam i at angle_min + i * angle_increment.
msg::LaserScan to_scan_message(const drivers::scip2::TimedScan& scan,
                               const drivers::scip2::SensorDescription& sensor,
                               const drivers::scip2::ScanRequest& request, std::uint64_t seq,
                               const dds::Source& source);

// Streams the sensor's scans into `publish` (true when written) until a stop is requested.
void stream_scip2_scans(const drivers::scip2::SensorAddress& address, const std::string& vehicle,
                        const Scip2SourceOptions& options,
                        const std::function<bool(const msg::LaserScan&)>& publish);

}  // namespace uavslam::lidar
