#include "drivers/mavlink/AutopilotClock.hpp"

#include <algorithm>

namespace uavslam::mavlink {
namespace {

constexpr double kRoundTripSlack = 1e-3;  // s beyond the shortest round trip still trusted
constexpr double kMinSpanForSlope = 1.0;  // s of autopilot time before the slope is fitted

}  // namespace

void AutopilotClock::add_round_trip(double host_sent, std::int64_t autopilot_ns,
                                    double host_received) {
  const double round_trip = host_received - host_sent;
  if (round_trip < 0) return;  // not an answer to a request of ours
  samples_.push_back(
      {static_cast<double>(autopilot_ns) * 1e-9, host_sent + round_trip / 2, round_trip});
  if (samples_.size() > window_) samples_.pop_front();
  last_round_trip_ = round_trip;
  ++round_trips_;
  fit();
}

void AutopilotClock::add_one_way(std::int64_t autopilot_ns, double host_received) {
  if (!fitted_) one_way_offset_ = host_received - static_cast<double>(autopilot_ns) * 1e-9;
}

void AutopilotClock::fit() {
  double shortest = samples_.front().round_trip;
  for (const Sample& s : samples_) shortest = std::min(shortest, s.round_trip);
  // Differences from the newest sample keep the sums small (autopilot and host times are large).
  const Sample& newest = samples_.back();
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const Sample& s : samples_) {
    if (s.round_trip > shortest + kRoundTripSlack) continue;
    const double x = s.autopilot - newest.autopilot;
    const double y = s.host - newest.host;
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double spread = sxx - sx * sx / n;
  const double span = newest.autopilot - samples_.front().autopilot;
  slope_ = (n >= 3 && span >= kMinSpanForSlope && spread > 0) ? (sxy - sx * sy / n) / spread : 1.0;
  // The line through the trusted samples' centroid with that slope.
  anchor_autopilot_ = newest.autopilot + sx / n;
  anchor_host_ = newest.host + sy / n;
  offset_ = anchor_host_ + slope_ * (newest.autopilot - anchor_autopilot_) - newest.autopilot;
  fitted_ = true;
}

std::optional<double> AutopilotClock::host_time(std::int64_t autopilot_ns) const {
  const double autopilot = static_cast<double>(autopilot_ns) * 1e-9;
  if (fitted_) return anchor_host_ + slope_ * (autopilot - anchor_autopilot_);
  if (one_way_offset_) return *one_way_offset_ + autopilot;
  return std::nullopt;
}

}  // namespace uavslam::mavlink
