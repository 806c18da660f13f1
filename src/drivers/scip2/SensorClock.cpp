#include "drivers/scip2/SensorClock.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>

namespace uavslam::drivers::scip2 {
namespace {

constexpr std::int64_t kWrap = std::int64_t{1} << 24;  // 4-character encoding: 24 bits of ms
constexpr std::size_t kMinBins = 3;                    // a line through fewer is a guess

}  // namespace

SensorClock::SensorClock(SensorClockOptions options) : options_(options) {}

void SensorClock::reset() {
  *this = SensorClock(options_);
}

double SensorClock::unwrap(std::uint32_t stamp_ms) {
  const std::uint32_t stamp = stamp_ms & static_cast<std::uint32_t>(kWrap - 1);
  if (!anchored_) {
    anchored_ = true;
    unwrapped_ms_ = stamp;
  } else {
    // The step from the last stamp, taken in [-2^23, 2^23): forward across a wrap, or a little
    // backwards (a TM answer read before a scan stamped earlier).
    std::int64_t step = (static_cast<std::int64_t>(stamp) - last_stamp_) % kWrap;
    if (step < 0) step += kWrap;
    if (step >= kWrap / 2) step -= kWrap;
    unwrapped_ms_ += step;
  }
  last_stamp_ = stamp;
  return static_cast<double>(unwrapped_ms_) * 1e-3;
}

void SensorClock::add_round_trip(double sent, std::uint32_t stamp_ms, double received) {
  const double sensor_s = unwrap(stamp_ms);
  const double duration = received - sent;
  if (duration < 0.0) return;
  if (round_trip_ && round_trip_->duration <= duration) return;
  round_trip_ = RoundTrip{sensor_s, (sent + received) / 2.0 - sensor_s, duration};
}

double SensorClock::add_arrival(std::uint32_t stamp_ms, double received) {
  const double sensor_s = unwrap(stamp_ms);
  const double delay = received - sensor_s;
  min_delay_ = arrivals_.empty() && !envelope_ready_ ? delay : std::min(min_delay_, delay);
  arrivals_.push_back({sensor_s, delay});
  while (!arrivals_.empty() && arrivals_.front().sensor_s < sensor_s - options_.window_s) {
    arrivals_.pop_front();
  }
  fit_envelope();
  // The latency is measured against the TM offset while the TM trip is inside the window (the
  // envelope is known best there); later the fitted line carries it.
  if (envelope_ready_ && round_trip_ && sensor_s - round_trip_->sensor_s < options_.window_s) {
    latency_ = envelope_at(round_trip_->sensor_s) - round_trip_->offset;
  }
  return sensor_s;
}

void SensorClock::fit_envelope() {
  struct Bin {
    Arrival lowest;
    std::size_t count = 0;
  };
  std::map<std::int64_t, Bin> bins;  // the arrival with the smallest delay in each bin
  std::size_t most = 0;
  for (const Arrival& a : arrivals_) {
    Bin& bin = bins[static_cast<std::int64_t>(std::floor(a.sensor_s / options_.bin_s))];
    if (bin.count == 0 || a.delay < bin.lowest.delay) bin.lowest = a;
    most = std::max(most, ++bin.count);
  }
  // A bin the window cuts, or the one still filling, has a minimum of fewer samples: higher,
  // and at the ends of the line, where it tilts the slope most. Only full bins count.
  if (!bins.empty()) bins.erase(std::prev(bins.end()));
  std::map<std::int64_t, Arrival> lowest;
  for (const auto& [index, bin] : bins) {
    if (2 * bin.count >= most) lowest[index] = bin.lowest;
  }
  if (lowest.size() < kMinBins) return;
  double mean_x = 0.0;
  double mean_y = 0.0;
  for (const auto& [bin, a] : lowest) {
    mean_x += a.sensor_s;
    mean_y += a.delay;
  }
  const auto n = static_cast<double>(lowest.size());
  mean_x /= n;
  mean_y /= n;
  double sxx = 0.0;
  double sxy = 0.0;
  for (const auto& [bin, a] : lowest) {
    sxx += (a.sensor_s - mean_x) * (a.sensor_s - mean_x);
    sxy += (a.sensor_s - mean_x) * (a.delay - mean_y);
  }
  if (sxx <= 0.0) return;
  slope_ = sxy / sxx;
  intercept_ = mean_y;
  centre_ = mean_x;
  envelope_ready_ = true;
}

std::optional<double> SensorClock::to_host(double sensor_s) const {
  if (envelope_ready_) return sensor_s + envelope_at(sensor_s) - (round_trip_ ? latency_ : 0.0);
  if (round_trip_) return sensor_s + round_trip_->offset;
  if (!arrivals_.empty()) return sensor_s + min_delay_;
  return std::nullopt;
}

}  // namespace uavslam::drivers::scip2
