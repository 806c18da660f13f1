// The moment a sensor process keeps its writers after its last sample. BEST_EFFORT has no
// acknowledgement: a process that exits right after its last write unmaps the shared-memory
// segment holding that sample, and a reader still behind (a loaded host) loses it (seen under
// `ctest -j2`: the last scan of a flight missing at the matcher and the recorder).
#pragma once

#include <chrono>
#include <thread>

#include "common/StopRequest.hpp"

namespace uavslam::process {

inline constexpr std::chrono::milliseconds kReaderGrace{300};

// Waits kReaderGrace, unless a stop was requested (Ctrl-C ends at once).
inline void give_readers_the_last_samples() {
  using Clock = std::chrono::steady_clock;
  const auto until = Clock::now() + kReaderGrace;
  while (!stop_requested() && Clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace uavslam::process
