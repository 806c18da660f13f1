#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/ImuBuffer.hpp"

namespace uavslam {
namespace {

ImuSample yaw_sample(double stamp, double yaw) {
  ImuSample s;
  s.stamp = stamp;
  s.orientation = Eigen::AngleAxisd(yaw, Vec3::UnitZ());
  return s;
}

double yaw_of(const Eigen::Quaterniond& q) {
  const Eigen::Matrix3d R = q.toRotationMatrix();
  return std::atan2(R(1, 0), R(0, 0));
}

TEST(ImuBuffer, InterpolatesBetweenSamplesAtTheScanTime) {
  ImuBuffer buffer(0.1);
  buffer.add(yaw_sample(1.000, 0.0));
  buffer.add(yaw_sample(1.005, 0.1));
  const auto q = buffer.orientation_at(1.002);
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR(yaw_of(*q), 0.04, 1e-9);
}

// The gyro's rate at a beam's time, for the sweep's deskew: linear between the samples around it,
// the nearest one just outside them, none beyond the gap.
TEST(ImuBuffer, GivesTheRateBetweenSamplesAsTheOrientation) {
  ImuBuffer buffer(0.05);
  ImuSample first = yaw_sample(1.000, 0.0);
  first.angular_velocity = Vec3(0.0, 0.0, 1.0);
  ImuSample second = yaw_sample(1.010, 0.01);
  second.angular_velocity = Vec3(0.0, 0.2, 2.0);
  buffer.add(first);
  buffer.add(second);
  ASSERT_TRUE(buffer.angular_velocity_at(1.0025).has_value());
  EXPECT_TRUE(buffer.angular_velocity_at(1.0025)->isApprox(Vec3(0.0, 0.05, 1.25), 1e-9));
  EXPECT_TRUE(buffer.angular_velocity_at(1.04)->isApprox(second.angular_velocity, 1e-12));
  EXPECT_FALSE(buffer.angular_velocity_at(1.2).has_value());
}

TEST(ImuBuffer, HoldsTheNearestSampleJustOutsideAndNothingFarther) {
  ImuBuffer buffer(0.05);
  EXPECT_FALSE(buffer.orientation_at(1.0).has_value());
  buffer.add(yaw_sample(1.0, 0.3));
  buffer.add(yaw_sample(1.01, 0.4));
  ASSERT_TRUE(buffer.orientation_at(1.04).has_value());
  EXPECT_NEAR(yaw_of(*buffer.orientation_at(1.04)), 0.4, 1e-9);
  EXPECT_NEAR(yaw_of(*buffer.orientation_at(0.97)), 0.3, 1e-9);
  EXPECT_FALSE(buffer.orientation_at(1.2).has_value());
  EXPECT_FALSE(buffer.orientation_at(0.5).has_value());
}

TEST(ImuBuffer, RefusesToInterpolateAcrossALongGap) {
  ImuBuffer buffer(0.05);
  buffer.add(yaw_sample(1.0, 0.0));
  buffer.add(yaw_sample(2.0, 1.0));
  EXPECT_FALSE(buffer.orientation_at(1.5).has_value());
  ASSERT_TRUE(buffer.orientation_at(1.04).has_value());
  EXPECT_NEAR(yaw_of(*buffer.orientation_at(1.04)), 0.0, 1e-9);
}

TEST(ImuBuffer, RejectsOutOfOrderAndNonFiniteSamples) {
  ImuBuffer buffer(0.1);
  buffer.add(yaw_sample(2.0, 0.0));
  buffer.add(yaw_sample(1.0, 0.0));
  buffer.add(yaw_sample(std::numeric_limits<double>::quiet_NaN(), 0.0));
  ImuSample zero = yaw_sample(3.0, 0.0);
  zero.orientation.coeffs().setZero();
  buffer.add(zero);
  EXPECT_EQ(buffer.size(), 1u);
  EXPECT_EQ(buffer.rejected(), 3u);
}

TEST(ImuBuffer, ForgetsSamplesOlderThanItsHistory) {
  ImuBuffer buffer(0.1, 1.0);
  for (int i = 0; i <= 300; ++i) buffer.add(yaw_sample(i * 0.01, 0.0));
  EXPECT_LE(buffer.size(), 102u);
  EXPECT_FALSE(buffer.orientation_at(0.5).has_value());
  EXPECT_TRUE(buffer.orientation_at(2.5).has_value());
}

}  // namespace
}  // namespace uavslam
