// The loop of a simulated sensor process: take the source's samples in stamp order, wait for each
// one's turn on the (shared) timeline and publish it; count what was published and what was
// overdue (RealTimePacer.hpp), stop at the end of the requested duration or on Ctrl-C.
#pragma once

#include <chrono>
#include <cstdint>
#include <iostream>

#include "common/RealTimePacer.hpp"
#include "common/SimSourceOptions.hpp"

namespace uavslam::process {

struct StreamCounts {
  std::uint64_t published = 0;
  std::uint64_t missed = 0;  // overdue when their turn came, not published
};

// Holds the stream until `count` readers of the writer's topic matched (at most 30 s), so discovery
// loses no data; says how long that took. False when they did not come.
template <typename Writer>
bool wait_for_subscribers(const Writer& writer, int count, const char* process) {
  if (count <= 0) return true;
  const auto start = std::chrono::steady_clock::now();
  if (!writer.wait_for_matched(static_cast<std::size_t>(count), std::chrono::seconds(30))) {
    std::cerr << process << ": no " << count << " subscriber(s) of " << writer.topic()
              << " within 30 s\n";
    return false;
  }
  std::cerr << process << ": " << count << " subscriber(s) of " << writer.topic()
            << " matched after "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
            << " s\n";
  return true;
}

// next(Sample&): false when the source is exhausted; publish(const Sample&): true when written.
template <typename Sample, typename Next, typename Publish>
StreamCounts publish_paced(const SimSourceOptions& options, double flight_start, Next next,
                           Publish publish) {
  RealTimePacer pacer = make_pacer(options, flight_start);
  StreamCounts counts;
  Sample sample;
  while (next(sample) && within_duration(options, flight_start, sample.stamp)) {
    const RealTimePacer::Turn turn = pacer.wait_for_turn(sample.stamp);
    if (turn == RealTimePacer::Turn::Stopped) break;
    if (turn == RealTimePacer::Turn::Missed) {
      ++counts.missed;
      continue;
    }
    counts.published += publish(sample) ? 1 : 0;
  }
  return counts;
}

}  // namespace uavslam::process
