#include "dds/MessageScanGeometry.hpp"

namespace uavslam::dds {

std::shared_ptr<const ScanGeometry> MessageScanGeometry::for_message(
    const msg::LaserScan& message) {
  const std::size_t beams = message.ranges().size();
  if (geometry_ && beams == beams_ && message.angle_min() == angle_min_ &&
      message.angle_increment() == angle_increment_ && message.range_min() == range_min_ &&
      message.range_max() == range_max_) {
    return geometry_;
  }
  beams_ = beams;
  angle_min_ = message.angle_min();
  angle_increment_ = message.angle_increment();
  range_min_ = message.range_min();
  range_max_ = message.range_max();
  const int count = static_cast<int>(beams);
  ScanGeometry geometry = place_ ? place_(angle_min_, angle_increment_, count)
                                 : ScanGeometry::planar(angle_min_, angle_increment_, count);
  geometry.min_range = range_min_;
  geometry.max_range = range_max_;
  geometry_ = std::make_shared<const ScanGeometry>(std::move(geometry));
  return geometry_;
}

}  // namespace uavslam::dds
