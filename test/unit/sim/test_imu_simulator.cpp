#include <cmath>

#include <gtest/gtest.h>

#include "SimTestHelpers.hpp"
#include "core/Angles.hpp"
#include "sim/ImuSimulator.hpp"
#include "sim/LidarSimulator.hpp"

namespace uavslam::sim {
namespace {

ImuSpec noiseless_imu() {
  ImuSpec spec;
  spec.orientation_noise_std_deg = 0.0;
  spec.gyro_noise_std = 0.0;
  spec.accel_noise_std = 0.0;
  return spec;
}

// Sample standard deviation of each component of many vectors.
struct Spread {
  void add(const Vec3& v) {
    sum += v;
    sum_squares += v.cwiseProduct(v);
    ++count;
  }
  Vec3 mean() const { return sum / count; }
  Vec3 std_dev() const { return (sum_squares / count - mean().cwiseProduct(mean())).cwiseSqrt(); }
  Vec3 sum = Vec3::Zero();
  Vec3 sum_squares = Vec3::Zero();
  int count = 0;
};

TEST(ImuSimulator, NoiselessHoverReadsTheTruthAndOneG) {
  const Trajectory hover(testing::hover(Vec3(1.0, 2.0, 1.5), 30.0, 10.0));
  ImuSimulator imu(noiseless_imu(), 1);
  const ImuSample sample = imu.sample_at(hover, 4.0);
  EXPECT_DOUBLE_EQ(sample.stamp, 4.0);
  EXPECT_LT(sample.orientation.angularDistance(hover.pose_at(4.0).orientation), 1e-12);
  EXPECT_LT(sample.angular_velocity.norm(), 1e-9);
  EXPECT_LT((sample.linear_acceleration - Vec3(0.0, 0.0, kGravity)).norm(), 1e-9);
}

TEST(ImuSimulator, AccelerometerReadsSpecificForceAlongTheThrust) {
  const Trajectory dash({{0.0, Vec3(0.0, 0.0, 1.0), 0.0}, {4.0, Vec3(4.0, 0.0, 1.0), 0.0}});
  ImuSimulator imu(noiseless_imu(), 1);
  const ImuSample sample = imu.sample_at(dash, 0.5);
  const double thrust = (dash.acceleration_at(0.5) + kGravity * Vec3::UnitZ()).norm();
  EXPECT_GT(thrust, kGravity + 0.01);
  EXPECT_LT((sample.linear_acceleration - Vec3(0.0, 0.0, thrust)).norm(), 1e-9);
}

TEST(ImuSimulator, AnAccelerometerBiasAddsToTheSpecificForce) {
  const Trajectory hover(testing::hover(Vec3(1.0, 2.0, 1.5), 30.0, 10.0));
  ImuSpec spec = noiseless_imu();
  spec.accel_bias = Vec3(0.02, -0.01, 0.03);
  ImuSimulator imu(spec, 1);
  const ImuSample sample = imu.sample_at(hover, 4.0);
  EXPECT_LT((sample.linear_acceleration - Vec3(0.02, -0.01, kGravity + 0.03)).norm(), 1e-9);
}

TEST(ImuSimulator, YawDriftOfTwoDegreesPerMinuteGivesTwoDegreesAfterAMinute) {
  const Trajectory hover(testing::hover(Vec3(1.0, 2.0, 1.5), 0.0, 120.0));
  ImuSpec spec = noiseless_imu();
  spec.yaw_drift_deg_per_min = 2.0;
  ImuSimulator imu(spec, 1);
  for (const auto& [t, expected_deg] :
       {std::pair{0.0, 0.0}, {30.0, 1.0}, {60.0, 2.0}, {120.0, 4.0}}) {
    const Eigen::Quaterniond error =
        imu.sample_at(hover, t).orientation * hover.pose_at(t).orientation.conjugate();
    const Eigen::AngleAxisd drift(error);
    EXPECT_NEAR(rad_to_deg(drift.angle()), expected_deg, 1e-9) << "t = " << t;
    if (expected_deg > 0.0) {
      EXPECT_NEAR(drift.axis().z(), 1.0, 1e-9);  // about world up
    }
  }
}

// A drift that changes (a gyro warming up): 2 degrees a minute for the first minute, then -1.
TEST(ImuSimulator, ADriftThatChangesIsIntegratedStretchByStretch) {
  const Trajectory hover(testing::hover(Vec3(1.0, 2.0, 1.5), 0.0, 180.0));
  ImuSpec spec = noiseless_imu();
  spec.yaw_drift_deg_per_min = 2.0;
  spec.yaw_drift_changes = {{60.0, -1.0}};
  ImuSimulator imu(spec, 1);
  for (const auto& [t, expected_deg] :
       {std::pair{30.0, 1.0}, {60.0, 2.0}, {120.0, 1.0}, {180.0, 0.0}}) {
    const Eigen::Quaterniond error =
        imu.sample_at(hover, t).orientation * hover.pose_at(t).orientation.conjugate();
    EXPECT_NEAR(rad_to_deg(2.0 * std::atan2(error.z(), error.w())), expected_deg, 1e-9)
        << "t = " << t;
  }
}

TEST(ImuSimulator, DriftIsAppliedOnTheWorldSideOfATiltedAttitude) {
  const Trajectory dash({{0.0, Vec3(0.0, 0.0, 1.0), 0.0}, {60.0, Vec3(30.0, 0.0, 1.0), 0.0}});
  ImuSpec spec = noiseless_imu();
  spec.yaw_drift_deg_per_min = 2.0;
  ImuSimulator imu(spec, 1);
  const double t = 10.0;
  const Eigen::Quaterniond expected =
      Eigen::AngleAxisd(deg_to_rad(2.0 * t / 60.0), Vec3::UnitZ()) * dash.pose_at(t).orientation;
  EXPECT_LT(imu.sample_at(dash, t).orientation.angularDistance(expected), 1e-12);
}

TEST(ImuSimulator, NoiseHasTheConfiguredSpread) {
  const Trajectory hover(testing::hover(Vec3(1.0, 2.0, 1.5), 30.0, 100.0));
  const ImuSpec spec;  // 0.1 deg, 0.001 rad/s, 0.02 m/s^2
  ImuSimulator imu(spec, 9);
  Spread attitude, gyro, accel;
  for (int k = 0; k < 20000; ++k) {
    const double t = k * 0.005;
    const ImuSample sample = imu.sample_at(hover, t);
    const Eigen::AngleAxisd error(hover.pose_at(t).orientation.conjugate() * sample.orientation);
    attitude.add(rad_to_deg(error.angle()) * error.axis());
    gyro.add(sample.angular_velocity);
    accel.add(sample.linear_acceleration - Vec3(0.0, 0.0, kGravity));
  }
  // 20000 samples: a sample standard deviation is within about 1% of the true one.
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(attitude.std_dev()[axis], 0.1, 0.005);
    EXPECT_NEAR(gyro.std_dev()[axis], 0.001, 0.00005);
    EXPECT_NEAR(accel.std_dev()[axis], 0.02, 0.001);
    EXPECT_NEAR(accel.mean()[axis], 0.0, 0.001);
  }
}

TEST(ImuSimulator, SameSeedSameSamplesOtherSeedOtherNoise) {
  const Trajectory hover(testing::hover(Vec3(1.0, 2.0, 1.5), 30.0, 10.0));
  ImuSimulator first(ImuSpec{}, 4), second(ImuSpec{}, 4), other(ImuSpec{}, 5);
  const ImuSample a = first.sample_at(hover, 1.0);
  const ImuSample b = second.sample_at(hover, 1.0);
  const ImuSample c = other.sample_at(hover, 1.0);
  EXPECT_EQ(a.orientation.coeffs(), b.orientation.coeffs());
  EXPECT_EQ(a.angular_velocity, b.angular_velocity);
  EXPECT_EQ(a.linear_acceleration, b.linear_acceleration);
  EXPECT_NE(a.angular_velocity, c.angular_velocity);
}

TEST(ImuSimulator, NoiseIsIndependentOfTheLidarsUnderTheSameSeed) {
  // Were both streams one generator, the IMU's k-th draw would equal the LiDAR's k-th beam noise.
  const World world(testing::empty_room());
  LidarSpec lidar_spec;
  LidarSpec exact_spec = lidar_spec;
  exact_spec.range_noise_std = 0.0;
  LidarSimulator lidar(lidar_spec, world, 7), exact(exact_spec, world, 7);
  Pose pose;
  pose.position = Vec3(5.0, 4.0, 1.5);
  const Scan noisy_scan = lidar.scan_at(pose, 0.0, 0);
  const Scan exact_scan = exact.scan_at(pose, 0.0, 0);

  const ImuSpec imu_spec;
  ImuSimulator imu(imu_spec, 7);
  const Trajectory hover(testing::hover(pose.position, 0.0, 10.0));
  double sum_products = 0.0, sum_lidar_squares = 0.0, sum_imu_squares = 0.0;
  for (std::size_t sample = 0; sample < 100; ++sample) {
    const Vec3 accel_noise =
        (imu.sample_at(hover, 1.0).linear_acceleration - Vec3(0.0, 0.0, kGravity)) /
        imu_spec.accel_noise_std;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const std::size_t draw = 9 * sample + 6 + axis;  // the accelerometer's draws
      const double lidar_noise =
          (double(noisy_scan.ranges[draw]) - exact_scan.ranges[draw]) / lidar_spec.range_noise_std;
      sum_products += lidar_noise * accel_noise[int(axis)];
      sum_lidar_squares += lidar_noise * lidar_noise;
      sum_imu_squares += accel_noise[int(axis)] * accel_noise[int(axis)];
    }
  }
  EXPECT_LT(std::abs(sum_products) / std::sqrt(sum_lidar_squares * sum_imu_squares), 0.2);
}

}  // namespace
}  // namespace uavslam::sim
