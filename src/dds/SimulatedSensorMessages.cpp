#include "dds/SimulatedSensorMessages.hpp"

#include "core/Angles.hpp"
#include "dds/Conversions.hpp"

namespace uavslam::dds {

msg::LaserScan simulated_scan_message(const Scan& scan, const LidarSpec& lidar,
                                      const std::string& vehicle) {
  const double fov = deg_to_rad(lidar.fov_deg);
  const double increment = fov / (lidar.beams - 1);
  return to_msg(scan, -fov / 2.0, increment, Source{"laser", vehicle});
}

msg::Imu simulated_imu_message(const ImuSample& sample, std::uint64_t seq,
                               const std::string& vehicle) {
  return to_msg(sample, seq, Source{"imu", vehicle});
}

msg::PoseWithCovarianceStamped ground_truth_message(const Pose& truth, std::uint64_t scan_seq,
                                                    std::uint64_t seq, const std::string& vehicle) {
  return to_msg(truth, 1.0f, scan_seq, seq, Source{"world", vehicle});
}

}  // namespace uavslam::dds
