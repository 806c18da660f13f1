// imu_bridge's `mavlink:` source: a real autopilot (PX4, ArduPilot) over UDP or a serial port.
// Publishes `imu` from its attitude/IMU messages (our frames, host-time stamps), and sends the
// matcher's `pose` back as VISION_POSITION_ESTIMATE (or ODOMETRY) so the autopilot can hold
// position on uavslam. The protocol lives in src/drivers/mavlink; this is the DDS wiring.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "common/NodeOptions.hpp"
#include "common/SimSourceOptions.hpp"
#include "io/YamlReader.hpp"

namespace uavslam::process {

struct MavlinkOptions {
  std::string bind_address = "127.0.0.1";  // UDP: the address the port is bound on
  std::string pose_message = "vision";     // "vision" (VISION_POSITION_ESTIMATE) or "odometry"
  double status_period = 5.0;              // s between status lines on stderr
  double attitude_rate = 200.0;  // Hz of ATTITUDE_QUATERNION asked of the autopilot; 0: not asked
  double imu_rate = 200.0;       // Hz of HIGHRES_IMU asked of the autopilot; 0: not asked
  // m/s: publish `velocity` from LOCAL_POSITION_NED, stated to this; 0: not (the default: only
  // an autopilot whose velocity comes from its own optical flow or VIO, not from our poses)
  double velocity_sigma = 0.0;
  double velocity_rate = 20.0;  // Hz of LOCAL_POSITION_NED asked of the autopilot (when read)
};

// Registers --mavlink-bind, --mavlink-pose, --mavlink-status-period, --mavlink-attitude-rate,
// --mavlink-imu-rate, --mavlink-velocity-sigma, --mavlink-velocity-rate.
void add_mavlink_options(CLI::App& app, MavlinkOptions& options);
// The keys of the same names (mavlink_bind, mavlink_pose, mavlink_status_period,
// mavlink_attitude_rate, mavlink_imu_rate, mavlink_velocity_sigma, mavlink_velocity_rate) from the
// process's config section, where the command line left them unset.
void apply_mavlink_config(const CLI::App& app, const io::YamlReader& section,
                          MavlinkOptions& options);
std::vector<std::string> mavlink_config_keys();

// True for a `mavlink:udp:PORT` or `mavlink:serial:DEVICE:BAUD` source.
bool is_mavlink_source(const std::string& source);
// "" when `source` is a well-formed mavlink source, else what is wrong with it.
std::string mavlink_source_problem(const std::string& source);

// Runs until SIGINT/SIGTERM; the process's exit code.
int bridge_autopilot(const NodeOptions& node, const SimSourceOptions& source,
                     const MavlinkOptions& options);

}  // namespace uavslam::process
