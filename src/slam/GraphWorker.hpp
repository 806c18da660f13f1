// The back end's keyframe graph (backend/KeyframeGraph) beside the front end: on a thread of its
// own, so that the scan's path never waits for a loop search or an optimisation (slam_matcher),
// or inline, in the caller's thread, so that a run over a log is the same every time (uavslam
// run, offline, simulate). The front end hands each keyframe over and, when it is ready to,
// takes the latest update: the keyframes where the graph puts them and the correction from its
// own frame to the graph's.
//
// Frames: the front end's map is in frame g, the number of updates it has taken. A keyframe
// handed over in frame g reaches a graph that may have moved on to g' > g; it is brought there by
// the corrections in between. An update carries the correction from the frame the front end is
// in (the last update it took) to the graph's, so updates the front end did not take yet are
// folded into the newest one.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "backend/KeyframeGraph.hpp"
#include "core/SlamConfig.hpp"
#include "core/SlamPipeline.hpp"

namespace uavslam {

struct GraphKeyframe {
  backend::NodePose pose;  // in the front end's frame `frame`
  Points points;           // what it added to the map, likewise
  std::vector<Vec3> normals;
  std::size_t frame = 0;
  // When not empty: once this keyframe is in, every keyframe's heading turned by these (the
  // drift the front end learnt since they were made; KeyframeGraph::turn_headings).
  std::vector<double> heading_turns;
  // x-y covariance (m^2) along what its scan left blind (KeyframeGraph::add), likewise.
  Eigen::Matrix2d unseen = Eigen::Matrix2d::Zero();
};

struct GraphUpdate {
  backend::MapCorrection correction;     // from the front end's frame to the graph's
  std::size_t frame = 0;                 // the graph's: the front end's once it applies this
  std::vector<MapKeyframe> keyframes;    // the first ones the front end made, in the graph's frame
  std::vector<backend::NodePose> poses;  // theirs
  std::size_t headings_turned = 0;       // GraphKeyframe::heading_turns applied so far
};

class GraphWorker {
 public:
  enum class Threading { Inline, Thread };
  GraphWorker(const SlamConfig::LoopClosure& config, Threading threading);
  ~GraphWorker();
  GraphWorker(const GraphWorker&) = delete;
  GraphWorker& operator=(const GraphWorker&) = delete;

  // Hands a keyframe over (inline: searched and optimised before it returns).
  void add(GraphKeyframe keyframe);
  // The newest update not taken yet; the front end is in its frame from then on.
  std::optional<GraphUpdate> take();
  // Waits for the keyframes handed over, optimises the whole graph once more; take() then has
  // the final update.
  void finish();

  backend::LoopCounts counts() const;
  double seconds() const;  // spent searching and optimising
  // The graph's keyframe poses (after finish(): the final ones).
  std::vector<backend::NodePose> poses() const;

 private:
  void run();
  void process(GraphKeyframe keyframe);
  void publish(const backend::MapCorrection& correction);
  backend::MapCorrection since(std::size_t frame) const;
  void account(std::chrono::steady_clock::time_point started);

  backend::KeyframeGraph graph_;                     // the worker's alone (inline: the caller's)
  std::vector<backend::MapCorrection> corrections_;  // [g]: frame g to g + 1
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable idle_;
  std::deque<GraphKeyframe> queue_;
  std::optional<GraphUpdate> ready_;
  std::size_t taken_frame_ = 0;  // the front end's frame
  std::size_t headings_turned_ = 0;
  bool busy_ = false;
  bool stop_ = false;
  backend::LoopCounts counts_;
  double seconds_ = 0.0;
  std::vector<backend::NodePose> poses_;
  std::thread thread_;  // last: started once the rest is built
};

}  // namespace uavslam
