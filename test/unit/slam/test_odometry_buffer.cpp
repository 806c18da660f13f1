#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "slam/OdometryBuffer.hpp"

namespace uavslam {
namespace {

OdometrySample at(double stamp, double x, double y) {
  return {stamp, Vec3(x, y, 0.0)};
}

TEST(OdometryBuffer, InterpolatesLinearlyBetweenTheSamplesAroundTheStamp) {
  OdometryBuffer buffer(0.1);
  ASSERT_TRUE(buffer.add(at(1.0, 0.0, 0.0)));
  ASSERT_TRUE(buffer.add(at(1.1, 1.0, -2.0)));
  const auto p = buffer.position_at(1.025);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(p->x(), 0.25, 1e-9);
  EXPECT_NEAR(p->y(), -0.5, 1e-9);
}

TEST(OdometryBuffer, ASampleAtTheStampIsTakenAsItIs) {
  OdometryBuffer buffer(0.1);
  buffer.add(at(1.0, 3.0, 4.0));
  const auto p = buffer.position_at(1.0);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(*p, Vec3(3.0, 4.0, 0.0));
}

TEST(OdometryBuffer, NeverExtrapolatesBeyondItsSamples) {
  OdometryBuffer buffer(0.1);
  buffer.add(at(1.0, 0.0, 0.0));
  buffer.add(at(1.1, 1.0, 0.0));
  EXPECT_FALSE(buffer.position_at(1.11).has_value());
  EXPECT_FALSE(buffer.position_at(0.99).has_value());
  EXPECT_FALSE(OdometryBuffer(0.1).position_at(1.0).has_value());
}

TEST(OdometryBuffer, SamplesFartherThanTheMaxGapGiveNoPosition) {
  OdometryBuffer buffer(0.1);
  buffer.add(at(1.0, 0.0, 0.0));
  buffer.add(at(1.5, 1.0, 0.0));
  EXPECT_FALSE(buffer.position_at(1.2).has_value()) << "0.2 s from the sample before";
  EXPECT_FALSE(buffer.position_at(1.35).has_value()) << "0.35 s from the sample before";
  EXPECT_TRUE(buffer.position_at(1.5).has_value());
}

TEST(OdometryBuffer, RejectsAndCountsNonFiniteAndOutOfOrderSamples) {
  OdometryBuffer buffer(0.1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(buffer.add(at(nan, 0.0, 0.0)));
  EXPECT_FALSE(buffer.add(at(1.0, inf, 0.0)));
  EXPECT_FALSE(buffer.add(at(1.0, 0.0, nan)));
  EXPECT_TRUE(buffer.add(at(1.0, 0.0, 0.0)));
  EXPECT_FALSE(buffer.add(at(1.0, 1.0, 0.0))) << "the same stamp again";
  EXPECT_FALSE(buffer.add(at(0.9, 1.0, 0.0))) << "back in time";
  EXPECT_EQ(buffer.rejected(), 5u);
  EXPECT_EQ(buffer.size(), 1u);
  EXPECT_FALSE(buffer.position_at(nan).has_value());
}

TEST(OdometryBuffer, KeepsAtMostItsCapacityDroppingTheOldest) {
  OdometryBuffer buffer(0.1, 3);
  for (int i = 0; i < 5; ++i) buffer.add(at(i * 0.05, i, 0.0));
  EXPECT_EQ(buffer.size(), 3u);
  EXPECT_FALSE(buffer.position_at(0.05).has_value()) << "dropped";
  const auto p = buffer.position_at(0.1);
  ASSERT_TRUE(p.has_value());
  EXPECT_DOUBLE_EQ(p->x(), 2.0);
}

}  // namespace
}  // namespace uavslam
