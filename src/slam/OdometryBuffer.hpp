// The recent positions of a second motion source (wheel odometry), so a scan gets the odometry's
// position at its own time. The matcher process turns two of them into the motion prior of
// SlamPipeline::process_scan: the odometry's motion from the last scan that got a pose to this one.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>

#include "core/Types.hpp"

namespace uavslam {

class OdometryBuffer {
 public:
  // max_gap: how far in time from t the samples a position at t is taken from may lie.
  // capacity: how many samples are kept (the oldest go first).
  explicit OdometryBuffer(double max_gap, std::size_t capacity = 2000);

  // Samples must come in time order with a finite stamp and position; others are rejected and
  // counted. False when rejected.
  bool add(const OdometrySample& sample);

  // The sample stamped t, or the linear interpolation between the two samples around t when both
  // lie within max_gap of it; none otherwise (never extrapolated: a held position would be a
  // motion the odometry did not report).
  std::optional<Vec3> position_at(double t) const;

  std::size_t size() const { return samples_.size(); }
  std::size_t rejected() const { return rejected_; }

 private:
  double max_gap_;
  std::size_t capacity_;
  std::deque<OdometrySample> samples_;
  std::size_t rejected_ = 0;
};

}  // namespace uavslam
