#include "core/nearest_neighbour/ParallelLoop.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

namespace uavslam {
namespace {

// How many times each item ran.
std::vector<int> runs_of(ParallelLoop& loop, std::size_t count, std::size_t chunk) {
  std::vector<std::atomic<int>> runs(count);
  loop.run(count, chunk, [&](std::size_t begin, std::size_t end) {
    ASSERT_LT(begin, end);
    ASSERT_LE(end, count);
    for (std::size_t i = begin; i < end; ++i) runs[i].fetch_add(1);
  });
  std::vector<int> counts;
  for (const auto& r : runs) counts.push_back(r.load());
  return counts;
}

TEST(ParallelLoop, EveryItemRunsOnceWhateverTheCountAndChunk) {
  ParallelLoop loop(3);
  ASSERT_EQ(loop.helpers(), 3u);
  for (std::size_t count : {0u, 1u, 15u, 16u, 17u, 180u, 1000u}) {
    for (std::size_t chunk : {0u, 1u, 16u, 64u}) {
      const std::vector<int> runs = runs_of(loop, count, chunk);
      for (std::size_t i = 0; i < count; ++i) {
        ASSERT_EQ(runs[i], 1) << "item " << i << " of " << count << ", chunk " << chunk;
      }
    }
  }
}

// The helpers share the work when they are awake: with slow items, some run off the caller's
// thread.
TEST(ParallelLoop, TheHelpersTakeAShare) {
  ParallelLoop loop(1);
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> elsewhere{0};
  for (int attempt = 0; attempt < 50 && elsewhere.load() == 0; ++attempt) {
    loop.run(64, 1, [&](std::size_t, std::size_t) {
      if (std::this_thread::get_id() != caller) elsewhere.fetch_add(1);
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    });
  }
  EXPECT_GT(elsewhere.load(), 0);
}

// A helper that has gone to sleep is woken by the next loop, and a loop started while another
// thread's runs is done alone, completely.
TEST(ParallelLoop, SleepingHelpersAndASecondCallerStillRunEveryItem) {
  ParallelLoop loop(2);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(runs_of(loop, 500, 8), std::vector<int>(500, 1));
  std::vector<int> first;
  std::vector<int> second;
  std::thread other([&] {
    for (int i = 0; i < 200; ++i) first = runs_of(loop, 300, 4);
  });
  for (int i = 0; i < 200; ++i) second = runs_of(loop, 300, 4);
  other.join();
  EXPECT_EQ(first, std::vector<int>(300, 1));
  EXPECT_EQ(second, std::vector<int>(300, 1));
}

TEST(ParallelLoop, WithoutHelpersTheCallerRunsItAll) {
  ParallelLoop loop(0);
  const std::thread::id caller = std::this_thread::get_id();
  bool elsewhere = false;
  loop.run(100, 10, [&](std::size_t, std::size_t) {
    elsewhere = elsewhere || std::this_thread::get_id() != caller;
  });
  EXPECT_FALSE(elsewhere);
}

}  // namespace
}  // namespace uavslam
