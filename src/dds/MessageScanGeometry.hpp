// The beam layout a scan message carries (angle_min, angle_increment, range_min, range_max, the
// number of ranges), as the core's geometry: a planar scanner at the body origin. For receivers
// that know nothing of the sensor but what each scan says, such as a replayed 2D laser log
// (lidar_driver --source carmen:FILE), where the scanner's frame is the robot's odometry frame.
// Or, given how to place a layout on the vehicle (a sensor's mount and floor mirror), that: a
// real sensor whose scans have another beam count than its configuration.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>

#include <msg/LaserScan.h>

#include "core/Types.hpp"

namespace uavslam::dds {

class MessageScanGeometry {
 public:
  // Beam i at angle_min + i * angle_increment as a geometry (its ranges are set from the message).
  using Place = std::function<ScanGeometry(double angle_min, double angle_increment, int beams)>;

  // A planar scanner at the body origin.
  MessageScanGeometry() = default;
  explicit MessageScanGeometry(Place place) : place_(std::move(place)) {}

  // The geometry of this message's layout; the same object while the layout does not change.
  std::shared_ptr<const ScanGeometry> for_message(const msg::LaserScan& message);

 private:
  Place place_;
  std::shared_ptr<const ScanGeometry> geometry_;
  std::size_t beams_ = 0;
  float angle_min_ = 0.0f;
  float angle_increment_ = 0.0f;
  float range_min_ = 0.0f;
  float range_max_ = 0.0f;
};

}  // namespace uavslam::dds
