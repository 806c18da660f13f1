// The motion prior of SlamPipeline::process_scan from a stream of odometry positions: the
// odometry's motion from the last scan that got a pose (accepted or dead-reckoned) to this one, as
// `uavslam run --carmen` gives it from the log, here for odometry arriving as samples on their own
// (the matcher process's `odom` topic). Unknown at either end (no sample close enough): none, the
// seed's "no motion model", counted.
// Its covariance: the last pose's, grown by the odometry's error over the motion,
//   Sigma = Sigma_posed + (floor + per_metre |motion|)^2 I   (wheel slip grows with the distance).
#pragma once

#include <cstddef>
#include <optional>

#include "core/MotionPrediction.hpp"
#include "core/SlamConfig.hpp"
#include "slam/OdometryBuffer.hpp"

namespace uavslam {

class OdometryPrior {
 public:
  OdometryPrior(double max_gap, const SlamConfig::Motion& noise, std::size_t capacity = 2000);

  // False (counted in rejected()) for a non-finite or out-of-order sample.
  bool add(const OdometrySample& sample) { return buffer_.add(sample); }

  // The odometry's motion from the last posed scan to the scan stamped t, in the odometry frame.
  MotionPrediction motion_to(double t);
  // The scan stamped t got a pose with this covariance: the next motion starts from the
  // odometry's position at t.
  void scan_posed(double t, const Eigen::Matrix3d& covariance);

  std::size_t scans_with_prior() const { return with_prior_; }
  std::size_t scans_without_prior() const { return without_prior_; }
  std::size_t rejected() const { return buffer_.rejected(); }

 private:
  OdometryBuffer buffer_;
  SlamConfig::Motion noise_;
  std::optional<Vec3> last_posed_;
  Eigen::Matrix3d posed_covariance_ = Eigen::Matrix3d::Zero();
  std::size_t with_prior_ = 0;
  std::size_t without_prior_ = 0;
};

}  // namespace uavslam
