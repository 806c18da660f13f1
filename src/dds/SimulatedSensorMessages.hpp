// The messages of the simulated sensors, as lidar_driver and imu_bridge (--source sim) publish
// them and `uavslam simulate --log` records them, so a recorded flight replays exactly like the
// live one: the LiDAR's beams from -fov/2 in equal steps (frame "laser"), the IMU's samples
// (frame "imu"), and the simulator's true body pose at each scan (frame "world"), recorded on the
// ground_truth channel for scoring a replay or an offline run.
#pragma once

#include <cstdint>
#include <string>

#include <msg/Imu.h>
#include <msg/LaserScan.h>
#include <msg/Pose.h>

#include "core/Types.hpp"
#include "sensor/LidarSpec.hpp"

namespace uavslam::dds {

// The recording channel of the true body pose at each scan (PoseWithCovarianceStamped).
inline constexpr char kGroundTruthTopic[] = "ground_truth";

msg::LaserScan simulated_scan_message(const Scan& scan, const LidarSpec& lidar,
                                      const std::string& vehicle);
msg::Imu simulated_imu_message(const ImuSample& sample, std::uint64_t seq,
                               const std::string& vehicle);
// quality 1 (it is the truth), scan_seq: the scan's sequence number.
msg::PoseWithCovarianceStamped ground_truth_message(const Pose& truth, std::uint64_t scan_seq,
                                                    std::uint64_t seq, const std::string& vehicle);

}  // namespace uavslam::dds
