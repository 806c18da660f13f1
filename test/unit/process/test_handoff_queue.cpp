#include "common/HandoffQueue.hpp"

#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace uavslam::process {
namespace {

using namespace std::chrono_literals;
using ::testing::ElementsAre;

TEST(HandoffQueue, HandsOverEverythingInArrivalOrder) {
  HandoffQueue<std::string> queue;
  EXPECT_TRUE(queue.push("a"));
  EXPECT_TRUE(queue.push("b"));
  std::vector<std::string> out{"stale"};
  EXPECT_TRUE(queue.take_all(out, 0ms));
  EXPECT_THAT(out, ElementsAre("a", "b"));
  EXPECT_TRUE(queue.take_all(out, 0ms));
  EXPECT_TRUE(out.empty()) << "nothing waits any more";
}

TEST(HandoffQueue, RefusesBeyondItsCapacityInsteadOfBlocking) {
  HandoffQueue<int> queue(2);
  EXPECT_TRUE(queue.push(1));
  EXPECT_TRUE(queue.push(2));
  EXPECT_FALSE(queue.push(3));
  std::vector<int> out;
  queue.take_all(out, 0ms);
  EXPECT_THAT(out, ElementsAre(1, 2));
  EXPECT_TRUE(queue.push(4)) << "room again once taken";
}

TEST(HandoffQueue, AfterCloseItDrainsThenSaysNothingMoreComes) {
  HandoffQueue<int> queue;
  queue.push(1);
  queue.close();
  EXPECT_FALSE(queue.push(2));
  std::vector<int> out;
  EXPECT_TRUE(queue.take_all(out, 0ms));
  EXPECT_THAT(out, ElementsAre(1));
  EXPECT_FALSE(queue.take_all(out, 0ms));
}

TEST(HandoffQueue, AWaitingTakerWakesForAnItemFromAnotherThread) {
  HandoffQueue<int> queue;
  std::thread producer([&] { queue.push(7); });
  std::vector<int> out;
  // Well past any scheduling delay; the taker returns as soon as the item is there.
  while (out.empty()) ASSERT_TRUE(queue.take_all(out, 10s));
  producer.join();
  EXPECT_THAT(out, ElementsAre(7));
}

}  // namespace
}  // namespace uavslam::process
