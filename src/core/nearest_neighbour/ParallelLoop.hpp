// A loop over independent items shared between the caller's thread and helper threads (one per
// further core): the caller and the helpers claim chunks of the items from a shared counter, and
// the caller never waits for a helper that has not claimed one. On a machine whose other cores
// are busy (the sensors' and recorder's processes beside the matcher) the helpers find nothing
// left to claim and the loop costs what it costs on one thread; with a core free it is shared.
// (An OpenMP team waits at its barrier for every thread, running or not: tried, the matchers of
// two TwoHosts tests in `make test` fell behind and dropped 146 and 452 of 801 scans.)
//
// One loop at a time: a second thread calling run() while a loop runs does its loop alone.
// Which thread runs an item does not change what the item computes.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace uavslam {

class ParallelLoop {
 public:
  // body(begin, end) runs items [begin, end).
  using Body = std::function<void(std::size_t begin, std::size_t end)>;

  explicit ParallelLoop(std::size_t helpers);
  ~ParallelLoop();
  ParallelLoop(const ParallelLoop&) = delete;
  ParallelLoop& operator=(const ParallelLoop&) = delete;

  // Runs body over [0, count) in chunks of `chunk` items; returns when every item has run.
  void run(std::size_t count, std::size_t chunk, const Body& body);

  std::size_t helpers() const { return threads_.size(); }

  // The process's loop, with a helper per core beyond the first.
  static ParallelLoop& shared();

 private:
  struct Loop {
    const Body* body = nullptr;
    std::size_t count = 0;
    std::size_t chunk = 1;
    std::atomic<std::size_t> next{0};
  };
  static void work_on(Loop& loop);
  void help();

  std::atomic<Loop*> current_{nullptr};
  std::atomic<std::size_t> busy_{0};      // helpers between looking at current_ and done with it
  std::atomic<std::size_t> sleeping_{0};  // helpers waiting on wake_
  std::atomic<bool> stop_{false};
  std::mutex owner_;  // held by the thread whose loop runs
  std::mutex sleep_mutex_;
  std::condition_variable wake_;
  std::vector<std::thread> threads_;  // last: started once the rest is built
};

}  // namespace uavslam
