// The matcher's scan queue: scans that arrive together are all handed over, oldest first; a scan
// that lags the newest by more than the backlog is skipped and counted, so memory and latency
// stay bounded when the matcher falls behind.
#include "ScanQueue.hpp"

#include <chrono>
#include <vector>

#include <gtest/gtest.h>

#include "dds/Conversions.hpp"

namespace uavslam::matcher {
namespace {

using namespace std::chrono_literals;

ReceivedScan scan_at(double stamp, std::uint32_t seq) {
  ReceivedScan scan;
  scan.message.header().stamp(dds::to_msg_time(stamp));
  scan.message.header().seq(seq);
  return scan;
}

ImuSample imu_at(double stamp) {
  ImuSample sample;
  sample.stamp = stamp;
  return sample;
}

std::vector<std::uint32_t> drain(ScanQueue& queue) {
  std::vector<std::uint32_t> seqs;
  while (auto work = queue.wait_for_scan(0ms, 0ms))
    seqs.push_back(work->scan.message.header().seq());
  return seqs;
}

TEST(ScanQueue, ABurstWithinTheBacklogIsHandedOverInOrder) {
  ScanQueue queue(false, 0.25);
  for (std::uint32_t i = 0; i < 8; ++i) queue.push_scan(scan_at(10.0 + 0.025 * i, i));
  EXPECT_EQ(drain(queue), (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(queue.scans_received(), 8u);
  EXPECT_EQ(queue.scans_skipped(), 0u);
}

TEST(ScanQueue, ScansLaggingTheNewestBeyondTheBacklogAreSkipped) {
  ScanQueue queue(false, 0.2625);
  for (std::uint32_t i = 0; i < 40; ++i) queue.push_scan(scan_at(10.0 + 0.025 * i, i));
  // Newest at 10.975 s: those stamped 10.7125 s or later remain, from 10.725 s (seq 29) on.
  const std::vector<std::uint32_t> left = drain(queue);
  ASSERT_FALSE(left.empty());
  EXPECT_EQ(left.front(), 29u);
  EXPECT_EQ(left.back(), 39u);
  EXPECT_EQ(queue.scans_skipped(), 29u);
}

TEST(ScanQueue, ZeroBacklogKeepsOnlyTheNewest) {
  ScanQueue queue(false, 0.0);
  for (std::uint32_t i = 0; i < 5; ++i) queue.push_scan(scan_at(1.0 + 0.025 * i, i));
  EXPECT_EQ(drain(queue), (std::vector<std::uint32_t>{4}));
  EXPECT_EQ(queue.scans_skipped(), 4u);
}

TEST(ScanQueue, AStampJumpBackwardsDropsTheOldTimeline) {
  ScanQueue queue(false, 0.25);
  queue.push_scan(scan_at(500.0, 1));
  queue.push_scan(scan_at(0.0, 0));  // a restarted driver
  EXPECT_EQ(drain(queue), (std::vector<std::uint32_t>{0}));
}

TEST(ScanQueue, ScansWithOneStampAreBoundedByCount) {
  ScanQueue queue(false, 0.25, 10);
  for (std::uint32_t i = 0; i < 25; ++i) queue.push_scan(scan_at(3.0, i));
  EXPECT_EQ(drain(queue).size(), 10u);
  EXPECT_EQ(queue.scans_skipped(), 15u);
}

TEST(ScanQueue, EachScanComesWithTheImuReceivedSoFar) {
  ScanQueue queue(false, 0.25);
  queue.push_imu(imu_at(1.0));
  queue.push_scan(scan_at(1.0, 0));
  queue.push_imu(imu_at(1.01));
  queue.push_scan(scan_at(1.025, 1));
  auto first = queue.wait_for_scan(0ms, 0ms);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->imu.size(), 2u);
  auto second = queue.wait_for_scan(0ms, 0ms);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->scan.message.header().seq(), 1u);
  EXPECT_TRUE(second->imu.empty()) << "already handed over with the first";
}

}  // namespace
}  // namespace uavslam::matcher
