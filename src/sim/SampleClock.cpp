#include "sim/SampleClock.hpp"

#include <cmath>
#include <stdexcept>

namespace uavslam::sim {

namespace {

std::uint64_t samples_between(double start, double end, double rate_hz) {
  if (!(rate_hz > 0.0)) throw std::invalid_argument("SampleClock: rate_hz must be > 0");
  if (end < start) return 0;
  // The tolerance keeps a final stamp that lands on `end` up to rounding.
  return static_cast<std::uint64_t>(std::floor((end - start) * rate_hz + 1e-9)) + 1;
}

}  // namespace

SampleClock::SampleClock(double start, double end, double rate_hz)
    : start_(start), rate_hz_(rate_hz), count_(samples_between(start, end, rate_hz)) {}

}  // namespace uavslam::sim
