#include "KeyframeQueue.hpp"

#include <iterator>

namespace uavslam::map_server {

void KeyframeQueue::push(const msg::MapPoints& keyframe) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queued_.push_back(keyframe);
  }
  changed_.notify_all();
}

std::vector<msg::MapPoints> KeyframeQueue::take_all(
    std::chrono::steady_clock::time_point deadline) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait_until(lock, deadline, [&] { return !queued_.empty(); });
  std::vector<msg::MapPoints> taken(std::make_move_iterator(queued_.begin()),
                                    std::make_move_iterator(queued_.end()));
  queued_.clear();
  return taken;
}

}  // namespace uavslam::map_server
