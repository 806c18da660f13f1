// Stamps start + k / rate for k = 0, 1, ... up to end: computed from k, never accumulated, so
// every process that replays the same clock gets bit-identical stamps.
#pragma once

#include <cstdint>

namespace uavslam::sim {

class SampleClock {
 public:
  SampleClock(double start, double end, double rate_hz);

  std::uint64_t count() const { return count_; }
  double stamp(std::uint64_t k) const { return start_ + static_cast<double>(k) / rate_hz_; }

 private:
  double start_;
  double rate_hz_;
  std::uint64_t count_;
};

}  // namespace uavslam::sim
