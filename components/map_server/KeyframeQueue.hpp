// Between the DDS receive thread and the map server's main thread: every received keyframe
// (`map_points` sample) waits here until the main thread ray-casts it, so the receive thread never
// blocks on the octree. None may be lost (each carries points no later keyframe repeats).
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <vector>

#include <msg/MapPoints.h>

namespace uavslam::map_server {

class KeyframeQueue {
 public:
  void push(const msg::MapPoints& keyframe);

  // Waits until a keyframe is queued or `deadline` passes, then takes all that are queued (none
  // on timeout).
  std::vector<msg::MapPoints> take_all(std::chrono::steady_clock::time_point deadline);

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<msg::MapPoints> queued_;
};

}  // namespace uavslam::map_server
