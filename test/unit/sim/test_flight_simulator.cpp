#include <algorithm>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "SimTestHelpers.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam::sim {
namespace {

std::vector<Scan> all_scans(FlightSimulator& simulator) {
  std::vector<Scan> scans;
  Scan scan;
  while (simulator.next_scan(scan)) scans.push_back(scan);
  return scans;
}

std::vector<ImuSample> all_imu_samples(FlightSimulator& simulator) {
  std::vector<ImuSample> samples;
  ImuSample sample;
  while (simulator.next_imu(sample)) samples.push_back(sample);
  return samples;
}

void expect_identical(const std::vector<Scan>& a, const std::vector<Scan>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].stamp, b[i].stamp);
    ASSERT_EQ(a[i].sequence, b[i].sequence);
    ASSERT_EQ(a[i].ranges, b[i].ranges) << "scan " << i;
  }
}

void expect_identical(const std::vector<ImuSample>& a, const std::vector<ImuSample>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].stamp, b[i].stamp);
    ASSERT_EQ(a[i].orientation.coeffs(), b[i].orientation.coeffs()) << "sample " << i;
    ASSERT_EQ(a[i].angular_velocity, b[i].angular_velocity) << "sample " << i;
    ASSERT_EQ(a[i].linear_acceleration, b[i].linear_acceleration) << "sample " << i;
  }
}

class FlightSimulatorTest : public ::testing::Test {
 protected:
  Scenario scenario_ = testing::shipped_scenario("short");
};

TEST_F(FlightSimulatorTest, ScanStreamCoversTheFlightAtTheLidarRate) {
  FlightSimulator simulator(scenario_);
  const std::vector<Scan> scans = all_scans(simulator);
  const double duration = simulator.end_time() - simulator.start_time();
  ASSERT_EQ(scans.size(), static_cast<std::size_t>(duration * scenario_.lidar.rate_hz) + 1);
  for (std::size_t k = 0; k < scans.size(); ++k) {
    EXPECT_EQ(scans[k].sequence, k);
    EXPECT_EQ(scans[k].stamp, simulator.start_time() + double(k) / scenario_.lidar.rate_hz);
    EXPECT_EQ(scans[k].geometry, simulator.scan_geometry());
    EXPECT_EQ(scans[k].ranges.size(), simulator.scan_geometry()->directions.size());
  }
  EXPECT_DOUBLE_EQ(scans.back().stamp, simulator.end_time());
  Scan extra;
  EXPECT_FALSE(simulator.next_scan(extra));
}

TEST_F(FlightSimulatorTest, ImuStreamCoversTheFlightAtTheImuRate) {
  FlightSimulator simulator(scenario_);
  const std::vector<ImuSample> samples = all_imu_samples(simulator);
  const double duration = simulator.end_time() - simulator.start_time();
  ASSERT_EQ(samples.size(), static_cast<std::size_t>(duration * scenario_.imu.rate_hz) + 1);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    EXPECT_EQ(samples[k].stamp, simulator.start_time() + double(k) / scenario_.imu.rate_hz);
  }
}

// The autopilot's velocity: at its rate over the flight, the true velocity turned by the IMU's
// heading drift, within its stated noise; none without the scenario's velocity section.
TEST_F(FlightSimulatorTest, VelocityStreamIsTheTrueVelocityInTheImusHeadingFrame) {
  VelocitySample sample;
  EXPECT_FALSE(FlightSimulator(scenario_).next_velocity(sample)) << "short.yaml has none";
  scenario_.velocity.rate_hz = 10.0;
  scenario_.velocity.noise_std = 0.01;
  scenario_.imu.yaw_drift_deg_per_min = 30.0;  // 5 degrees after 10 s: a frame to be seen
  FlightSimulator simulator(scenario_);
  std::vector<VelocitySample> samples;
  while (simulator.next_velocity(sample)) samples.push_back(sample);
  const double duration = simulator.end_time() - simulator.start_time();
  ASSERT_EQ(samples.size(), static_cast<std::size_t>(duration * 10.0) + 1);
  double worst = 0.0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double t = simulator.start_time() + double(k) / 10.0;
    EXPECT_EQ(samples[k].stamp, t);
    EXPECT_TRUE(samples[k].covariance.isApprox(1e-4 * Eigen::Matrix3d::Identity()));
    const Vec3 in_heading_frame = heading_drift_at(scenario_.imu, simulator.trajectory(), t) *
                                  simulator.trajectory().velocity_at(t);
    worst = std::max(worst, (samples[k].velocity - in_heading_frame).norm());
  }
  EXPECT_LT(worst, 0.06) << "about five sigmas of 0.01 m/s in three axes";
  EXPECT_GT(worst, 0.0);
}

// A late scan (faults.late_scan_every): stamped as the others, it sees the world from where the
// body was late_scan_s before (its sweep too); the scans around it are on time.
TEST_F(FlightSimulatorTest, ALateScanSeesTheWorldFromEarlier) {
  scenario_.lidar.range_noise_std = 0.0;
  scenario_.faults.late_scan_every = 4;
  scenario_.faults.late_scan_s = 0.5;
  FlightSimulator simulator(scenario_);
  const std::vector<Scan> scans = all_scans(simulator);
  LidarSimulator lidar(scenario_.lidar, simulator.world(), scenario_.seed);
  const Trajectory& trajectory = simulator.trajectory();
  for (std::size_t k = 100; k < 108; ++k) {
    const double stamp = scans[k].stamp;
    EXPECT_EQ(stamp, simulator.start_time() + double(k) / scenario_.lidar.rate_hz);
    const bool late = k % 4 == 3;
    const Scan expected = lidar.scan_along(trajectory, late ? stamp - 0.5 : stamp, stamp, k);
    EXPECT_EQ(scans[k].ranges, expected.ranges) << "scan " << k << (late ? " (late)" : "");
  }
}

TEST_F(FlightSimulatorTest, SameScenarioGivesBitIdenticalStreams) {
  FlightSimulator first(scenario_);
  FlightSimulator second(scenario_);
  expect_identical(all_scans(first), all_scans(second));
  expect_identical(all_imu_samples(first), all_imu_samples(second));
}

TEST_F(FlightSimulatorTest, StreamsDoNotDependOnEachOther) {
  FlightSimulator lidar_first(scenario_);
  FlightSimulator imu_first(scenario_);
  const std::vector<ImuSample> imu_drained_first = all_imu_samples(imu_first);
  expect_identical(all_scans(lidar_first), all_scans(imu_first));
  expect_identical(all_imu_samples(lidar_first), imu_drained_first);
}

TEST_F(FlightSimulatorTest, InterleavingDoesNotChangeTheStreams) {
  FlightSimulator interleaved(scenario_);
  FlightSimulator separate(scenario_);
  std::vector<Scan> scans;
  std::vector<ImuSample> samples;
  Scan scan;
  ImuSample sample;
  bool more = true;
  while (more) {  // in time order, as one process serving both streams would
    more = false;
    for (int i = 0; i < 5 && interleaved.next_imu(sample); ++i) {
      samples.push_back(sample);
      more = true;
    }
    if (interleaved.next_scan(scan)) {
      scans.push_back(scan);
      more = true;
    }
  }
  expect_identical(scans, all_scans(separate));
  expect_identical(samples, all_imu_samples(separate));
}

TEST_F(FlightSimulatorTest, OtherSeedGivesOtherNoise) {
  FlightSimulator first(scenario_);
  Scenario reseeded = scenario_;
  reseeded.seed += 1;
  FlightSimulator other(reseeded);
  Scan a, b;
  ASSERT_TRUE(first.next_scan(a) && other.next_scan(b));
  EXPECT_NE(a.ranges, b.ranges);
  ImuSample c, d;
  ASSERT_TRUE(first.next_imu(c) && other.next_imu(d));
  EXPECT_NE(c.angular_velocity, d.angular_velocity);
}

TEST_F(FlightSimulatorTest, GroundTruthIsTheTrajectory) {
  FlightSimulator simulator(scenario_);
  EXPECT_EQ(simulator.start_time(), scenario_.waypoints.front().t);
  EXPECT_EQ(simulator.end_time(), scenario_.waypoints.back().t);
  for (const Waypoint& w : scenario_.waypoints) {
    EXPECT_LT((simulator.ground_truth_at(w.t).position - w.position).norm(), 1e-9);
  }
  EXPECT_EQ(simulator.ground_truth_at(7.3).position, simulator.trajectory().pose_at(7.3).position);
  EXPECT_TRUE(simulator.world().is_free(simulator.ground_truth_at(7.3).position));
}

TEST_F(FlightSimulatorTest, MovedSimulatorKeepsStreaming) {
  FlightSimulator original(scenario_);
  FlightSimulator reference(scenario_);
  Scan scan;
  ASSERT_TRUE(original.next_scan(scan));
  FlightSimulator moved(std::move(original));
  std::vector<Scan> rest = all_scans(moved);
  rest.insert(rest.begin(), scan);
  expect_identical(rest, all_scans(reference));
}

}  // namespace
}  // namespace uavslam::sim
