// One laser line of a CARMEN log as a vehicle's sensors would give it: the scan, the orientation
// source's sample (the odometry heading: the robots of these logs had no IMU) and the wheel
// odometry's position, all at the scan's timeline stamp (CarmenTimeline.hpp). The one adapter from
// CARMEN logs to the pipeline's inputs, for the log tools (`uavslam run`, `offline --carmen`) and
// the DDS replay (lidar_driver and imu_bridge --source carmen:FILE).
#pragma once

#include <cstddef>
#include <memory>

#include "core/Types.hpp"
#include "io/CarmenScanStream.hpp"

namespace uavslam::io {

// Which body the samples describe.
enum class CarmenBody {
  // The robot (its odometry pose); the scan's geometry carries the laser's mount on it. For the
  // log tools, which hand the scan to the pipeline as it is.
  Robot,
  // The laser itself, at the body origin: for scans that travel without their mount (a LaserScan
  // message has none, and the matcher places such a scan at the body origin).
  Laser,
};

struct CarmenSamples {
  ImuSample orientation;    // the heading alone: no rates or accelerations were logged
  OdometrySample odometry;  // planar
  Scan scan;                // sequence: the scan's 0-based index in the log
};

class CarmenSensor {
 public:
  explicit CarmenSensor(CarmenBody body) : body_(body) {}

  // heading_offset (rad) is added to the logged heading: the robustness probe of `uavslam run
  // --heading-jitter`; 0 otherwise.
  CarmenSamples samples_of(const TimedCarmenScan& timed, double heading_offset = 0.0);

 private:
  std::shared_ptr<const ScanGeometry> geometry_for(const CarmenScan& scan);

  CarmenBody body_;
  // One geometry per distinct beam layout and mount (a log normally has one), so the beam
  // directions are computed once per layout.
  std::shared_ptr<const ScanGeometry> geometry_;
  std::size_t beams_ = 0;
  double start_ = 0.0;
  double increment_ = 0.0;
  double max_range_ = 0.0;
};

}  // namespace uavslam::io
