// Between a DDS receive thread and a process's worker thread: items wait here in arrival order
// until the worker takes them all at once, so the receive thread never waits for the worker's
// slow work (ray casting, the disk). Bounded: a worker that falls behind costs memory up to
// `capacity` items; beyond that push() refuses the item (the caller counts the drop) rather than
// block the DDS thread that delivered it.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <iterator>
#include <limits>
#include <mutex>
#include <utility>
#include <vector>

namespace uavslam::process {

template <typename T>
class HandoffQueue {
 public:
  explicit HandoffQueue(std::size_t capacity = std::numeric_limits<std::size_t>::max())
      : capacity_(capacity) {}

  // False when the queue is full or closed: the item is dropped.
  bool push(T item) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (closed_ || items_.size() >= capacity_) return false;
      items_.push_back(std::move(item));
    }
    changed_.notify_one();
    return true;
  }

  // Waits up to `timeout` for items and moves every waiting one into `out` (cleared first).
  // False once the queue is closed and empty: nothing more will come.
  bool take_all(std::vector<T>& out, std::chrono::milliseconds timeout) {
    out.clear();
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return closed_ || !items_.empty(); });
    out.assign(std::make_move_iterator(items_.begin()), std::make_move_iterator(items_.end()));
    items_.clear();
    return !(closed_ && out.empty());
  }

  // No more pushes; take_all hands out what is left, then returns false.
  void close() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    changed_.notify_all();
  }

 private:
  std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<T> items_;
  bool closed_ = false;
};

}  // namespace uavslam::process
