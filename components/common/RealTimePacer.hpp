// Publishes recorded or simulated data at the pace it was stamped with (or `rate` times faster).
//
// Two sensor processes of one simulated flight must publish on one timeline, or the matcher sees
// scans and IMU samples of different moments with the same stamp. Given a start time on the
// system clock (shared by processes of one host), the sample stamped `flight_start + d` is due at
// `start_at + d / rate` in every process, however late each one was ready; a sample already
// overdue when its turn comes is missed, as a powered sensor's data is while nobody listens.
// Without a start time the timeline starts at the first sample waited for.
#pragma once

#include <chrono>
#include <optional>

namespace uavslam::process {

class RealTimePacer {
 public:
  enum class Turn { Publish, Missed, Stopped };

  // start_at: seconds since the epoch of the system clock; flight_start: the stamp due then.
  explicit RealTimePacer(double rate = 1.0, std::optional<double> start_at = std::nullopt,
                         double flight_start = 0.0);

  // Sleeps until the sample stamped `stamp` is due (waking early on a stop request). Missed: the
  // sample was due more than a quarter second ago.
  Turn wait_for_turn(double stamp);

  // Waits like wait_for_turn, publishing missed samples too; false on a stop request.
  bool wait_until(double stamp);

 private:
  using Clock = std::chrono::system_clock;
  double rate_;
  std::optional<double> start_at_;
  double flight_start_;
};

}  // namespace uavslam::process
