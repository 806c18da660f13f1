#include "core/nearest_neighbour/ParallelLoop.hpp"

#include <algorithm>

namespace uavslam {
namespace {

// A helper with nothing to do looks again this many times (yielding its core to whoever wants
// it) before it sleeps: about the gap between two ICP iterations' searches, so that it is awake
// for the next one while a scan is matched, and asleep between scans.
constexpr int kLooksBeforeSleeping = 2000;

}  // namespace

ParallelLoop::ParallelLoop(std::size_t helpers) {
  for (std::size_t i = 0; i < helpers; ++i) threads_.emplace_back([this] { help(); });
}

ParallelLoop::~ParallelLoop() {
  {
    const std::lock_guard<std::mutex> lock(sleep_mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

ParallelLoop& ParallelLoop::shared() {
  static ParallelLoop loop(std::max(1u, std::thread::hardware_concurrency()) - 1);
  return loop;
}

void ParallelLoop::work_on(Loop& loop) {
  for (;;) {
    const std::size_t begin = loop.next.fetch_add(loop.chunk);
    if (begin >= loop.count) return;
    (*loop.body)(begin, std::min(begin + loop.chunk, loop.count));
  }
}

void ParallelLoop::run(std::size_t count, std::size_t chunk, const Body& body) {
  chunk = std::max<std::size_t>(chunk, 1);
  std::unique_lock<std::mutex> owner(owner_, std::try_to_lock);
  if (threads_.empty() || count <= chunk || !owner.owns_lock()) {
    if (count > 0) body(0, count);
    return;
  }
  Loop loop;
  loop.body = &body;
  loop.count = count;
  loop.chunk = chunk;
  current_.store(&loop);
  if (sleeping_.load() > 0) {
    { const std::lock_guard<std::mutex> lock(sleep_mutex_); }
    wake_.notify_all();
  }
  work_on(loop);
  // No helper looks at this loop once current_ no longer names it; those that already do are
  // counted in busy_ (they count themselves before they look), and finish their chunks.
  current_.store(nullptr);
  while (busy_.load() != 0) std::this_thread::yield();
}

void ParallelLoop::help() {
  int idle_looks = 0;
  while (!stop_.load()) {
    if (current_.load() != nullptr) {
      busy_.fetch_add(1);
      if (Loop* loop = current_.load()) work_on(*loop);
      busy_.fetch_sub(1);
      idle_looks = 0;
      continue;
    }
    if (++idle_looks < kLooksBeforeSleeping) {
      std::this_thread::yield();
      continue;
    }
    std::unique_lock<std::mutex> lock(sleep_mutex_);
    sleeping_.fetch_add(1);
    wake_.wait(lock, [this] { return stop_.load() || current_.load() != nullptr; });
    sleeping_.fetch_sub(1);
    idle_looks = 0;
  }
}

}  // namespace uavslam
