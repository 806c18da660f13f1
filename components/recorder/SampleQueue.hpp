// Between the DDS threads and the thread that writes the log: samples wait here, in arrival
// order, for the disk. Bounded, so a disk that falls behind costs memory only up to `capacity`
// samples; beyond that a new sample is dropped (and the caller counts it) rather than blocking the
// DDS thread that delivered it.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <vector>

namespace uavslam::recorder {

struct ReceivedSample {
  std::uint16_t channel = 0;
  std::int64_t receive_time_ns = 0;
  std::int64_t source_time_ns = 0;
  std::vector<std::uint8_t> cdr;
};

class SampleQueue {
 public:
  explicit SampleQueue(std::size_t capacity);

  // False when the queue is full or closed: the sample is dropped.
  bool push(ReceivedSample sample);
  // Waits up to `timeout` for samples and moves every waiting one into `out` (cleared first).
  // False once the queue is closed and empty: nothing more will come.
  bool pop_all(std::vector<ReceivedSample>& out, std::chrono::milliseconds timeout);
  // No more pushes; pop_all hands out what is left, then returns false.
  void close();

 private:
  std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<ReceivedSample> samples_;
  bool closed_ = false;
};

}  // namespace uavslam::recorder
