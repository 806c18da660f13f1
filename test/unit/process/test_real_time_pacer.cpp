#include "common/RealTimePacer.hpp"

#include <chrono>

#include <gtest/gtest.h>

namespace uavslam::process {
namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

TEST(RealTimePacer, ASampleDueLongAgoIsMissed) {
  // The flight started 10 s ago on the shared timeline: its first second is long overdue.
  RealTimePacer pacer(1.0, now_seconds() - 10.0, 0.0);
  EXPECT_EQ(pacer.wait_for_turn(0.0), RealTimePacer::Turn::Missed);
  EXPECT_EQ(pacer.wait_for_turn(1.0), RealTimePacer::Turn::Missed);
}

TEST(RealTimePacer, ASampleIsPublishedNotBeforeItsTurn) {
  const double start_at = now_seconds() + 0.05;
  RealTimePacer pacer(2.0, start_at, 100.0);
  // Stamp 100.1 at twice real time is due 0.05 s after the start.
  EXPECT_EQ(pacer.wait_for_turn(100.1), RealTimePacer::Turn::Publish);
  EXPECT_GE(now_seconds(), start_at + 0.05);
}

TEST(RealTimePacer, WithoutAStartTimeTheFirstSampleStartsTheTimeline) {
  RealTimePacer pacer(4.0);
  EXPECT_EQ(pacer.wait_for_turn(50.0), RealTimePacer::Turn::Publish);
  const double before = now_seconds();
  EXPECT_EQ(pacer.wait_for_turn(50.2), RealTimePacer::Turn::Publish);
  EXPECT_GE(now_seconds() - before, 0.04) << "0.2 s of flight at 4x is 0.05 s";
}

}  // namespace
}  // namespace uavslam::process
