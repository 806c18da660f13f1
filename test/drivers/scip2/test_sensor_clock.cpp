// The sensor clock mapping with synthetic clocks: a sensor clock that runs fast or slow (ppm),
// starts near its 24-bit wrap, stamps each scan at the sweep's start and delivers it a sweep
// later plus a random delay with occasional long stalls. The host stamps must stay within 2 ms of
// the truth (a scan period is 25 ms) for 15 minutes, across the wrap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "drivers/scip2/SensorClock.hpp"

namespace uavslam::drivers::scip2 {
namespace {

constexpr double kHostStart = 1.7e9;
constexpr double kPeriod = 0.025;   // 40 Hz
constexpr double kLatency = 0.025;  // the data leaves after the sweep
constexpr double kWrapS = 16777.216;

struct SyntheticSensor {
  double drift_ppm;
  double offset_s;  // the sensor clock at kHostStart

  std::uint32_t stamp_at(double host) const {
    const double sensor = (host - kHostStart) * (1.0 + drift_ppm * 1e-6) + offset_s;
    return static_cast<std::uint32_t>(static_cast<std::int64_t>(std::floor(sensor * 1e3)) %
                                      (std::int64_t{1} << 24));
  }
};

// The largest |host stamp - truth| over `minutes` of scans.
double worst_error(const SyntheticSensor& sensor, bool with_round_trips, double minutes) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> small_delay(0.0002, 0.003);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  SensorClock clock;
  double host = kHostStart;
  if (with_round_trips) {
    for (int i = 0; i < 10; ++i) {
      const double sent = host;
      const double read_at = sent + small_delay(random) / 4.0;
      const double received = read_at + small_delay(random) / 4.0;
      clock.add_round_trip(sent, sensor.stamp_at(read_at), received);
      host = received + 0.001;
    }
  }
  double worst = 0.0;
  const auto scans = static_cast<int>(minutes * 60.0 / kPeriod);
  for (int k = 0; k < scans; ++k) {
    const double truth = host + 0.01 + k * kPeriod;  // the sweep's start
    double delay = small_delay(random);
    if (unit(random) < 0.02) delay += 0.040;  // a stalled USB transfer
    const double sensor_s = clock.add_arrival(sensor.stamp_at(truth), truth + kLatency + delay);
    const auto stamp = clock.to_host(sensor_s);
    if (!stamp) return INFINITY;
    if (k > 0) worst = std::max(worst, std::abs(*stamp - truth));
  }
  return worst;
}

TEST(SensorClock, FollowsA100PpmFastClockAcrossTheWrap) {
  const SyntheticSensor sensor{100.0, kWrapS - 120.0};  // wraps after 2 minutes
  const double error = worst_error(sensor, true, 15.0);
  RecordProperty("worst_error_ms", std::to_string(error * 1e3));
  EXPECT_LT(error, 0.002);
}

TEST(SensorClock, FollowsA100PpmSlowClock) {
  EXPECT_LT(worst_error({-100.0, 12.345}, true, 15.0), 0.002);
}

TEST(SensorClock, WithoutRoundTripsStampsLagByTheLatency) {
  const double error = worst_error({100.0, 100.0}, false, 2.0);
  EXPECT_GT(error, kLatency - 0.002);  // the envelope alone cannot see the sweep's latency
}

TEST(SensorClock, EstimatesTheDrift) {
  SensorClock clock;
  const SyntheticSensor sensor{100.0, 50.0};
  for (int k = 0; k < 2400; ++k) {
    const double truth = kHostStart + k * kPeriod;
    clock.add_arrival(sensor.stamp_at(truth), truth + kLatency);
  }
  // host - sensor shrinks by 100 us per s of a clock 100 ppm fast
  EXPECT_NEAR(clock.drift_ppm(), -100.0, 10.0);
}

TEST(SensorClock, UnwrapsForwardAndSlightlyBackward) {
  SensorClock clock;
  EXPECT_DOUBLE_EQ(clock.unwrap((1u << 24) - 10), 16777.206);
  EXPECT_DOUBLE_EQ(clock.unwrap(5), 16777.221);
  EXPECT_DOUBLE_EQ(clock.unwrap(3), 16777.219);
}

}  // namespace
}  // namespace uavslam::drivers::scip2
