// The core geometry a scan message's ranges belong to.
//   - Without a sensor description: the beam layout the message carries (angle_min,
//     angle_increment, range_min, range_max, the number of ranges) as a planar scanner at the body
//     origin. For receivers that know nothing of the sensor but what each scan says, such as a
//     replayed 2D laser log (lidar_driver --source carmen:FILE), where the laser is the body.
//   - With one (a sensor file's `lidar`): the sensor's geometry (mount, floor mirror, rings). A
//     planar scan with another beam count keeps its own layout, placed on the vehicle as the
//     description says: a real UTM-30LX sends 1081 steps where the simulated one has 1080.
//   Either way a message's time_increment > 0 says when each beam fired (the geometry's fire
//   times), for the matcher's deskew (scan.deskew).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>

#include <msg/LaserScan.h>

#include "core/Types.hpp"
#include "sensor/LidarSpec.hpp"

namespace uavslam::dds {

class MessageScanGeometry {
 public:
  // A planar scanner at the body origin.
  MessageScanGeometry() = default;
  explicit MessageScanGeometry(const LidarSpec& lidar);

  // The geometry of this message; the same object while the layout does not change.
  std::shared_ptr<const ScanGeometry> for_message(const msg::LaserScan& message);

  // The sensor description's own geometry (null without one).
  const std::shared_ptr<const ScanGeometry>& sensor_geometry() const { return sensor_; }
  // A message's layout differed from the sensor description's, and its own was used.
  bool own_layout_used() const { return own_layout_used_; }

 private:
  std::shared_ptr<const ScanGeometry> layout_of(const msg::LaserScan& message);
  std::shared_ptr<const ScanGeometry> timed(const std::shared_ptr<const ScanGeometry>& geometry,
                                            float time_increment);

  std::optional<LidarSpec> lidar_;
  std::shared_ptr<const ScanGeometry> sensor_;
  bool own_layout_used_ = false;
  std::shared_ptr<const ScanGeometry> layout_;
  std::size_t beams_ = 0;
  float angle_min_ = 0.0f;
  float angle_increment_ = 0.0f;
  float range_min_ = 0.0f;
  float range_max_ = 0.0f;
  std::shared_ptr<const ScanGeometry> timed_;  // the last geometry given fire times, from
  std::shared_ptr<const ScanGeometry> timed_from_;
  float timed_increment_ = 0.0f;
};

}  // namespace uavslam::dds
