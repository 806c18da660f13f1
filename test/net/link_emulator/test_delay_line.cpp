#include "DelayLine.hpp"

#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace uavslam::net {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;
using Clock = DelayLine::Clock;

const Clock::time_point kStart{};

TEST(DelayLine, HoldsEachPacketForTheDelay) {
  DelayLine line({milliseconds(20), microseconds(0), 0.0, 1});
  ASSERT_TRUE(line.admit(1, kStart));
  ASSERT_TRUE(line.admit(2, kStart + milliseconds(5)));
  EXPECT_TRUE(line.release_due(kStart + milliseconds(19)).empty());
  EXPECT_EQ(line.release_due(kStart + milliseconds(20)), std::vector<std::uint32_t>{1});
  EXPECT_EQ(line.next_due(), kStart + milliseconds(25));
  EXPECT_EQ(line.release_due(kStart + milliseconds(30)), std::vector<std::uint32_t>{2});
  EXPECT_FALSE(line.next_due().has_value());
  EXPECT_EQ(line.counters().packets, 2u);
  EXPECT_EQ(line.counters().max_held, 2u);
}

TEST(DelayLine, ZeroDelayReleasesAtOnce) {
  DelayLine line({});
  ASSERT_TRUE(line.admit(7, kStart));
  EXPECT_EQ(line.release_due(kStart), std::vector<std::uint32_t>{7});
}

TEST(DelayLine, JitterStaysInItsBandAndNeverReorders) {
  DelayLine line({milliseconds(20), milliseconds(5), 0.0, 3});
  std::vector<std::uint32_t> released;
  Clock::time_point now = kStart;
  for (std::uint32_t id = 0; id < 1000; ++id) {
    ASSERT_TRUE(line.admit(id, now));
    const Clock::time_point due = *line.next_due();
    if (line.held() == 1) {
      EXPECT_GE(due, now + milliseconds(15));
      EXPECT_LE(due, now + milliseconds(25));
    }
    for (std::uint32_t r : line.release_due(now)) released.push_back(r);
    now += microseconds(300);
  }
  for (std::uint32_t r : line.release_due(now + milliseconds(30))) released.push_back(r);
  ASSERT_EQ(released.size(), 1000u);
  for (std::uint32_t i = 0; i < released.size(); ++i) EXPECT_EQ(released[i], i);
}

std::vector<bool> fates(std::uint64_t seed, double loss, int count) {
  DelayLine line({milliseconds(1), microseconds(0), loss, seed});
  std::vector<bool> kept;
  for (int i = 0; i < count; ++i) kept.push_back(line.admit(static_cast<std::uint32_t>(i), kStart));
  return kept;
}

TEST(DelayLine, LossIsTheGivenShareAndReproducibleBySeed) {
  const std::vector<bool> first = fates(42, 0.05, 20000);
  EXPECT_EQ(first, fates(42, 0.05, 20000));
  EXPECT_NE(first, fates(43, 0.05, 20000));
  int lost = 0;
  for (bool kept : first) lost += kept ? 0 : 1;
  EXPECT_GT(lost, 800);  // 5 % of 20000 is 1000; the binomial spread is about 31
  EXPECT_LT(lost, 1200);
}

TEST(DelayLine, NoLossKeepsAllAndFullLossKeepsNone) {
  for (bool kept : fates(5, 0.0, 1000)) EXPECT_TRUE(kept);
  for (bool kept : fates(5, 1.0, 1000)) EXPECT_FALSE(kept);
}

TEST(DelayLine, LostPacketsAreCountedAndNotHeld) {
  DelayLine line({milliseconds(10), microseconds(0), 1.0, 1});
  EXPECT_FALSE(line.admit(1, kStart));
  EXPECT_EQ(line.held(), 0u);
  EXPECT_EQ(line.counters().lost, 1u);
}

TEST(DelayLine, ReleaseAllEmptiesTheLineInOrder) {
  DelayLine line({milliseconds(100), microseconds(0), 0.0, 1});
  for (std::uint32_t id = 10; id < 13; ++id) line.admit(id, kStart);
  EXPECT_EQ(line.release_all(), (std::vector<std::uint32_t>{10, 11, 12}));
  EXPECT_EQ(line.held(), 0u);
}

TEST(DelayLine, RejectsImpossibleSettings) {
  EXPECT_THROW(DelayLine({milliseconds(1), microseconds(0), 1.5, 1}), std::invalid_argument);
  EXPECT_THROW(DelayLine({milliseconds(-1), microseconds(0), 0.0, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace uavslam::net
