#include "slam/GraphWorker.hpp"

#include <chrono>
#include <utility>

namespace uavslam {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

GraphWorker::GraphWorker(const SlamConfig::LoopClosure& config, Threading threading)
    : graph_(config) {
  if (threading == Threading::Thread) thread_ = std::thread([this] { run(); });
}

GraphWorker::~GraphWorker() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void GraphWorker::add(GraphKeyframe keyframe) {
  if (!thread_.joinable()) {
    process(std::move(keyframe));
    return;
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(keyframe));
  }
  wake_.notify_one();
}

void GraphWorker::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (stop_) return;
    GraphKeyframe keyframe = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    process(std::move(keyframe));
    lock.lock();
    busy_ = false;
    idle_.notify_all();
  }
}

// The keyframe brought from the front end's frame to the graph's (the corrections since), into
// the graph; an update when a loop moved the graph.
void GraphWorker::process(GraphKeyframe keyframe) {
  const auto started = Clock::now();
  const backend::MapCorrection to_graph = since(keyframe.frame);
  for (Vec3& p : keyframe.points) p = to_graph.transform * p;
  for (Vec3& n : keyframe.normals) n = to_graph.transform.linear() * n;
  const Eigen::Matrix2d turn = to_graph.transform.linear().topLeftCorner<2, 2>();
  const std::optional<backend::MapCorrection> moved =
      graph_.add(to_graph(keyframe.pose), keyframe.points, keyframe.normals,
                 turn * keyframe.unseen * turn.transpose());
  if (!keyframe.heading_turns.empty()) {
    // A loop's correction, if any, is folded into the turn's.
    if (moved) corrections_.push_back(*moved);
    ++headings_turned_;
    publish(graph_.turn_headings(keyframe.heading_turns));
  } else if (moved) {
    publish(*moved);
  }
  account(started);
}

// From frame `frame` to the graph's: the corrections in between, one after the other.
backend::MapCorrection GraphWorker::since(std::size_t frame) const {
  backend::MapCorrection total;
  for (std::size_t g = frame; g < corrections_.size(); ++g) total = total.then(corrections_[g]);
  return total;
}

// The counts as they now stand, and the time since `started` spent on the graph.
void GraphWorker::account(std::chrono::steady_clock::time_point started) {
  const std::lock_guard<std::mutex> lock(mutex_);
  counts_ = graph_.counts();
  seconds_ += std::chrono::duration<double>(Clock::now() - started).count();
}

void GraphWorker::publish(const backend::MapCorrection& correction) {
  corrections_.push_back(correction);
  GraphUpdate update;
  update.frame = corrections_.size();
  update.headings_turned = headings_turned_;
  update.keyframes.resize(graph_.size());
  for (std::size_t k = 0; k < graph_.size(); ++k) {
    update.poses.push_back(graph_.pose(k));
    update.keyframes[k].position = update.poses.back().position;
    update.keyframes[k].points = graph_.points_in_world(k);
    update.keyframes[k].normals = graph_.normals_in_world(k);
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  // From the frame the front end is in: the updates it has not taken are folded into this one.
  update.correction = since(taken_frame_);
  poses_ = update.poses;
  ready_ = std::move(update);
}

std::optional<GraphUpdate> GraphWorker::take() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!ready_) return std::nullopt;
  std::optional<GraphUpdate> update = std::move(ready_);
  ready_.reset();
  taken_frame_ = update->frame;
  return update;
}

void GraphWorker::finish() {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return queue_.empty() && !busy_; });
  }
  // The worker now waits for a keyframe that will not come: the graph is the caller's.
  const auto started = Clock::now();
  const std::optional<backend::MapCorrection> moved = graph_.optimise();
  if (moved) publish(*moved);
  account(started);
}

backend::LoopCounts GraphWorker::counts() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return counts_;
}

double GraphWorker::seconds() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return seconds_;
}

std::vector<backend::NodePose> GraphWorker::poses() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return poses_;
}

}  // namespace uavslam
