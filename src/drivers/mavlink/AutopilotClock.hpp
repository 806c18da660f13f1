// Maps the autopilot's clock (time since its boot: ATTITUDE's time_boot_ms, HIGHRES_IMU's
// time_usec, TIMESYNC's tc1 in ns) to host time, as host = a + b * autopilot, fitted by least
// squares over the last round trips of the TIMESYNC protocol (mavlink.io/en/services/timesync.html:
// we send tc1 = 0, ts1 = our time; the autopilot answers tc1 = its time, ts1 echoed). A round
// trip puts the autopilot's tc1 at the midpoint of our send and receive times; only round trips
// within 1 ms of the window's shortest take part, so a delayed answer does not bias the fit. The
// slope b follows the crystal's drift once the window spans a second. Until the first round trip,
// SYSTEM_TIME's time_boot_ms against its arrival gives a coarse offset (biased by the link delay).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

namespace uavslam::mavlink {

class AutopilotClock {
 public:
  explicit AutopilotClock(std::size_t window = 64) : window_(window) {}

  // A TIMESYNC answer: our request left at host_sent, the answer carried the autopilot's time
  // `autopilot_ns` and arrived at host_received (host times in s).
  void add_round_trip(double host_sent, std::int64_t autopilot_ns, double host_received);
  // A one-way time (SYSTEM_TIME's time_boot_ms, in ns) received at host_received.
  void add_one_way(std::int64_t autopilot_ns, double host_received);

  bool synchronised() const { return fitted_ || one_way_offset_.has_value(); }
  // Host time (s) of an autopilot time (ns since its boot); nullopt before any synchronisation.
  std::optional<double> host_time(std::int64_t autopilot_ns) const;
  // host - autopilot at the newest round trip (s), the fitted rate error (ppm), the newest round
  // trip's duration (s), and how many round trips were used.
  double offset() const { return offset_; }
  double drift_ppm() const { return (slope_ - 1.0) * 1e6; }
  double last_round_trip() const { return last_round_trip_; }
  std::size_t round_trips() const { return round_trips_; }

 private:
  struct Sample {
    double autopilot = 0;  // s
    double host = 0;       // s, the round trip's midpoint
    double round_trip = 0;
  };
  void fit();

  std::size_t window_;
  std::deque<Sample> samples_;
  std::optional<double> one_way_offset_;
  bool fitted_ = false;
  double anchor_autopilot_ = 0, anchor_host_ = 0, slope_ = 1.0, offset_ = 0;
  double last_round_trip_ = 0;
  std::size_t round_trips_ = 0;
};

}  // namespace uavslam::mavlink
