#include "SampleQueue.hpp"

#include <iterator>
#include <utility>

namespace uavslam::recorder {

SampleQueue::SampleQueue(std::size_t capacity) : capacity_(capacity) {}

bool SampleQueue::push(ReceivedSample sample) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_ || samples_.size() >= capacity_) return false;
    samples_.push_back(std::move(sample));
  }
  changed_.notify_one();
  return true;
}

bool SampleQueue::pop_all(std::vector<ReceivedSample>& out, std::chrono::milliseconds timeout) {
  out.clear();
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait_for(lock, timeout, [&] { return closed_ || !samples_.empty(); });
  out.assign(std::make_move_iterator(samples_.begin()), std::make_move_iterator(samples_.end()));
  samples_.clear();
  return !(closed_ && out.empty());
}

void SampleQueue::close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
}

}  // namespace uavslam::recorder
