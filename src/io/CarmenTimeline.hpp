// The clock of a CARMEN log replay. A log's ipc_timestamps may run backwards (intel.clf: 631
// times), while everything downstream (the ImuBuffer, a pacer) needs strictly increasing stamps.
// The timeline gives each scan, in file order, a stamp that equals its ipc_timestamp wherever the
// log's stamps increase and creeps forward by kStep wherever they do not, so a backwards step
// never moves time back and never makes a replay wait.
#pragma once

#include <cstddef>
#include <limits>

namespace uavslam::io {

class CarmenTimeline {
 public:
  static constexpr double kStep = 1e-4;  // s; far below any scan period (5-75 Hz lasers)

  // The stamp of the next scan in file order, given its ipc_timestamp.
  double next(double ipc_timestamp);

  // How many scans got a stamp other than their own (their ipc_timestamp did not increase).
  std::size_t adjusted() const { return adjusted_; }

 private:
  double last_ = -std::numeric_limits<double>::infinity();
  std::size_t adjusted_ = 0;
};

}  // namespace uavslam::io
