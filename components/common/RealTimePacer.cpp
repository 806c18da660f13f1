#include "common/RealTimePacer.hpp"

#include <algorithm>
#include <thread>

#include "common/StopRequest.hpp"

namespace uavslam::process {
namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

RealTimePacer::RealTimePacer(double rate, std::optional<double> start_at, double flight_start)
    : rate_(rate > 0.0 ? rate : 1.0), start_at_(start_at), flight_start_(flight_start) {}

RealTimePacer::Turn RealTimePacer::wait_for_turn(double stamp) {
  if (!start_at_) {
    start_at_ = now_seconds();
    flight_start_ = stamp;
  }
  const double due = *start_at_ + (stamp - flight_start_) / rate_;
  constexpr double kMaxLateness = 0.25;  // s
  // Short naps, so Ctrl-C is answered within a few tens of milliseconds.
  constexpr double kNap = 0.02;
  for (double now = now_seconds(); now < due; now = now_seconds()) {
    if (stop_requested()) return Turn::Stopped;
    std::this_thread::sleep_for(std::chrono::duration<double>(std::min(due - now, kNap)));
  }
  if (stop_requested()) return Turn::Stopped;
  return now_seconds() - due > kMaxLateness ? Turn::Missed : Turn::Publish;
}

bool RealTimePacer::wait_until(double stamp) {
  return wait_for_turn(stamp) != Turn::Stopped;
}

}  // namespace uavslam::process
