// The recent orientation samples of the IMU, so a scan gets the orientation at its own time
// (interpolated between the samples around it) rather than the latest one.
#pragma once

#include <deque>
#include <optional>

#include "core/Types.hpp"

namespace uavslam {

class ImuBuffer {
 public:
  // max_gap: the largest distance in time from a scan to the samples it is interpolated from.
  // history: how many seconds of samples are kept.
  explicit ImuBuffer(double max_gap, double history = 2.0);

  // Samples must come in time order with a finite stamp and orientation; others are rejected and
  // counted.
  void add(const ImuSample& sample);

  // Slerp between the samples around t; the nearest sample when t lies just outside them; none
  // when no sample is within max_gap.
  std::optional<Eigen::Quaterniond> orientation_at(double t) const;
  // The body's rate (rad/s, body frame) at t, interpolated as orientation_at.
  std::optional<Vec3> angular_velocity_at(double t) const;

  std::size_t size() const { return samples_.size(); }
  std::size_t rejected() const { return rejected_; }

 private:
  double max_gap_;
  double history_;
  std::deque<ImuSample> samples_;
  // The samples around t: both when within 2 max_gap of each other, else the nearer one if
  // within max_gap (first == second), else none; and t's fraction from the first to the second.
  struct Around {
    const ImuSample* first = nullptr;
    const ImuSample* second = nullptr;
    double fraction = 0.0;
  };
  std::optional<Around> around(double t) const;
  std::size_t rejected_ = 0;
};

}  // namespace uavslam
