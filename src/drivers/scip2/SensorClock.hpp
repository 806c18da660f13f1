// Maps the sensor's millisecond time stamps (24 bits, wrapping every 4.66 h: C-42-03320B
// section 8, MD "Time Stamp (4byte)") to host time, following drift.
//
// Two kinds of observation feed it:
// - round trips of the TM command (section 8, "TM-Command": TM1 answers the sensor's time): the
//   sensor read its clock between our send and our receive, so host = (sent + received) / 2 is
//   its time on the host clock to within half the round trip; the shortest trip wins.
// - scan arrivals: a scan's data reaches the host a latency after its time stamp (the sweep, the
//   transfer, the OS) plus a delay that is never negative. Over a sliding window the smallest
//   (arrival - stamp) per bin traces the minimum-delay envelope; a least-squares line through those
//   minima follows the clock rate difference (drift, ppm). The constant part of the latency, which
//   arrivals alone cannot see, is what the envelope lies above the TM offset.
// Host time of a stamp = stamp + envelope(stamp) - latency.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>

namespace uavslam::drivers::scip2 {

struct SensorClockOptions {
  double window_s = 60.0;  // arrivals older than this (sensor time) leave the fit
  double bin_s = 1.0;      // one envelope point (the minimum delay) per bin
};

class SensorClock {
 public:
  explicit SensorClock(SensorClockOptions options = {});

  // The stamp as seconds on a continuous sensor timeline (wraps undone; the first stamp seen
  // after reset() anchors it).
  double unwrap(std::uint32_t stamp_ms);

  // A TM1 round trip: sent at `sent`, answered `stamp_ms`, received at `received` (host s).
  void add_round_trip(double sent, std::uint32_t stamp_ms, double received);
  // A scan stamped `stamp_ms` that arrived at `received`; returns its unwrapped sensor time.
  double add_arrival(std::uint32_t stamp_ms, double received);

  // Host time of an unwrapped sensor time; nullopt before any observation.
  std::optional<double> to_host(double sensor_s) const;

  bool round_trip_seen() const { return round_trip_.has_value(); }
  double drift_ppm() const { return slope_ * 1e6; }
  double latency_s() const { return latency_; }
  double best_round_trip_s() const { return round_trip_ ? round_trip_->duration : 0.0; }

  // Forgets everything (a reconnected sensor may have been reset).
  void reset();

 private:
  struct Arrival {
    double sensor_s;
    double delay;  // host - sensor
  };
  struct RoundTrip {
    double sensor_s;
    double offset;  // host - sensor
    double duration;
  };

  void fit_envelope();
  double envelope_at(double sensor_s) const { return intercept_ + slope_ * (sensor_s - centre_); }

  SensorClockOptions options_;
  bool anchored_ = false;
  std::uint32_t last_stamp_ = 0;
  std::int64_t unwrapped_ms_ = 0;
  std::deque<Arrival> arrivals_;
  std::optional<RoundTrip> round_trip_;
  bool envelope_ready_ = false;
  double intercept_ = 0.0;
  double slope_ = 0.0;
  double centre_ = 0.0;
  double latency_ = 0.0;
  double min_delay_ = 0.0;
};

}  // namespace uavslam::drivers::scip2
