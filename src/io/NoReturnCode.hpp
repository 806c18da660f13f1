// The range a laser log writes when a beam got no return. FLASER lines carry no maximum range,
// and scanners differ: the SICK LMS 2xx of intel.clf writes 81.83 m, fr079.clf's 81.91 m, and
// aces.clf's 50.00 m. Taken for a real range, the code puts a wall of phantom points on an arc
// around the robot. A code is not a measurement: the scanner writes the very same value for every
// missing beam, so it is the log's largest range and repeats far more often than the ranges just
// below it, which real surfaces spread over many values.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>

namespace uavslam::io {

struct NoReturnCode {
  float range = 0.0f;        // m; this value and any larger one mean "no return"
  std::size_t readings = 0;  // how often the log writes it
};

class RangeTally {
 public:
  void add(float range);
  // The largest range, if it is a code: at least kMinReadings readings, and kMinRatio times as
  // many as any value within kBand below it. None for a log whose every beam returned.
  std::optional<NoReturnCode> no_return_code() const;

  static constexpr std::size_t kMinReadings = 20;
  static constexpr double kMinRatio = 10.0;
  static constexpr double kBand = 0.02;  // fraction of the range

 private:
  std::map<float, std::size_t> counts_;  // by value: the logs print centimetres, a few thousand
};

// One pass over the FLASER lines of a CARMEN log (ROBOTLASER1 states its own maximum range).
// A file that cannot be opened gives none; the reader that follows reports it.
std::optional<NoReturnCode> learn_flaser_no_return_code(const std::string& path);

}  // namespace uavslam::io
