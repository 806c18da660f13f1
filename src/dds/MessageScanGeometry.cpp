#include "dds/MessageScanGeometry.hpp"

#include "sensor/LidarGeometry.hpp"

namespace uavslam::dds {

MessageScanGeometry::MessageScanGeometry(const LidarSpec& lidar)
    : lidar_(lidar), sensor_(make_scan_geometry(lidar)) {}

std::shared_ptr<const ScanGeometry> MessageScanGeometry::for_message(
    const msg::LaserScan& message) {
  if (sensor_ && (message.ranges().size() == sensor_->directions.size() || lidar_->rings > 1)) {
    return timed(sensor_, message.time_increment());
  }
  if (sensor_) own_layout_used_ = true;
  return timed(layout_of(message), message.time_increment());
}

// A scanner that says when its beams fire (time_increment > 0) is taken at its word: the sensor
// file's sweep, if any, is the same scanner's on paper.
std::shared_ptr<const ScanGeometry> MessageScanGeometry::timed(
    const std::shared_ptr<const ScanGeometry>& geometry, float time_increment) {
  if (!(time_increment > 0.0f)) return geometry;
  if (timed_ && timed_from_ == geometry && timed_increment_ == time_increment) return timed_;
  ScanGeometry copy = *geometry;
  copy.sweep_beams_in_order(time_increment);
  timed_from_ = geometry;
  timed_increment_ = time_increment;
  timed_ = std::make_shared<const ScanGeometry>(std::move(copy));
  return timed_;
}

std::shared_ptr<const ScanGeometry> MessageScanGeometry::layout_of(const msg::LaserScan& message) {
  const std::size_t beams = message.ranges().size();
  if (layout_ && beams == beams_ && message.angle_min() == angle_min_ &&
      message.angle_increment() == angle_increment_ && message.range_min() == range_min_ &&
      message.range_max() == range_max_) {
    return layout_;
  }
  beams_ = beams;
  angle_min_ = message.angle_min();
  angle_increment_ = message.angle_increment();
  range_min_ = message.range_min();
  range_max_ = message.range_max();
  const int count = static_cast<int>(beams);
  ScanGeometry geometry = lidar_
                              ? planar_scan_geometry(*lidar_, angle_min_, angle_increment_, count)
                              : ScanGeometry::planar(angle_min_, angle_increment_, count);
  geometry.min_range = range_min_;
  geometry.max_range = range_max_;
  layout_ = std::make_shared<const ScanGeometry>(std::move(geometry));
  return layout_;
}

}  // namespace uavslam::dds
