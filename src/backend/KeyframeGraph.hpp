// The back end for one vehicle (issue 18): the front end's keyframes as the nodes of a pose graph
// (PoseGraph), each new one searched against older ones for a loop (CorrelativeMatcher), and an
// accepted loop optimised into the graph. The front end then re-anchors its map on the moved
// keyframes (SlamPipeline::replace_map) with the correction this returns.
//
// A loop is searched without trusting the current estimate beyond what the graph between the two
// allows: a keyframe at least min_travel back along the flight is a candidate when the estimate
// puts it within 3 sigma of the graph's best path between them (plus min_radius), and the search
// covers that window in x, y and yaw. A match is a loop only when it scores min_score, clearly
// beats the best look-alike elsewhere in the window, lays the surfaces on each other as they were
// seen, from the same side (SurfaceSides), and the rest of the graph agrees with it (PoseGraph
// switches off the ones it does not).
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "backend/PoseGraph.hpp"
#include "backend/SurfaceSides.hpp"
#include "core/SlamConfig.hpp"
#include "core/Types.hpp"

namespace uavslam::backend {

struct LoopCounts {
  std::size_t searches = 0;               // candidates searched
  std::size_t accepted = 0;               // loops in the graph, not switched off
  std::size_t rejected_score = 0;         // nothing in the window scored min_score
  std::size_t rejected_ambiguous = 0;     // a look-alike scored nearly as well, or a slope
  std::size_t rejected_back_to_back = 0;  // the surfaces it laid on each other faced each other
  std::size_t rejected_by_graph = 0;      // switched off by the optimisation: the rest disagreed
  std::size_t optimisations = 0;
};

// "12 accepted of 240 searched (rejected: 200 score, 20 look-alike, 1 back to back, 8 by the
// graph), 14 optimisations": how the tools and processes print the counts.
std::string describe(const LoopCounts& loops);

// World frame before an optimisation -> after, about the newest keyframe: what the front end
// applies to its pose and map (a turn about the vertical and a shift).
struct MapCorrection {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  double yaw = 0.0;  // rad, the turn's angle

  NodePose operator()(const NodePose& pose) const;  // a pose in the old frame, in the new
  // This correction, then `next`: from this one's old frame to next's new one.
  MapCorrection then(const MapCorrection& next) const;
};

// The correction that moves `before` onto `after` (and everything placed from it with it):
//   p' = R(after.yaw - before.yaw) (p - before.position) + after.position
MapCorrection correction_between(const NodePose& before, const NodePose& after);

class KeyframeGraph {
 public:
  explicit KeyframeGraph(const SlamConfig::LoopClosure& config);

  // A front-end keyframe: its pose (position and heading in the front end's current world frame)
  // and the points it added to the map with their normals (empty or one per point), world frame.
  // `unseen`: its position's covariance in x-y (m^2, world frame) along what its scan left blind,
  // the motion prior's since its last fix there (zero where the scan saw everything). Searches
  // it for loops; a correction when an accepted loop moved the newest keyframe.
  std::optional<MapCorrection> add(const NodePose& pose, const Points& points,
                                   const std::vector<Vec3>& normals,
                                   const Eigen::Matrix2d& unseen = Eigen::Matrix2d::Zero());

  // Optimises the whole graph once more (the end of a run); the correction as add()'s.
  std::optional<MapCorrection> optimise();

  // The front end's keyframes were made with headings off by -turns[k] (the drift of its
  // heading source, learnt after they were made; PoseGraph::turn_headings): the steps between
  // them turned, the graph optimised with its loops, and the correction as add()'s, always.
  MapCorrection turn_headings(const std::vector<double>& turns);

  std::size_t size() const { return nodes_.size(); }
  const NodePose& pose(std::size_t keyframe) const { return graph_.node(keyframe); }
  // A keyframe's points and normals where its pose now puts them.
  Points points_in_world(std::size_t keyframe) const;
  std::vector<Vec3> normals_in_world(std::size_t keyframe) const;
  const LoopCounts& counts() const { return counts_; }
  const PoseGraph& graph() const { return graph_; }

 private:
  struct Node {
    Points points;              // in the keyframe's heading frame (see to_node_frame)
    std::vector<Vec3> normals;  // likewise
    SurfacePoints slice;        // the points near the keyframe's height, in 2D, with their normals
    double travelled = 0.0;     // m along the flight from the first keyframe
    double reach = 0.0;         // m, to its farthest point
  };
  // A keyframe's uncertainty relative to another through the graph (uncertainty_from).
  struct PathUncertainty {
    double position = std::numeric_limits<double>::infinity();  // m^2, per horizontal axis
    double yaw = std::numeric_limits<double>::infinity();       // rad^2
  };
  struct Candidate {
    std::size_t keyframe = 0;
    double distance = 0.0;  // m, between the estimates
    double radius = 0.0;    // m, the window's half-width
    double angular = 0.0;   // rad
  };

  Constraint step_constraint(const NodePose& from, const NodePose& to,
                             const Eigen::Matrix2d& unseen_growth) const;
  std::vector<PathUncertainty> uncertainty_from(std::size_t newest) const;
  std::vector<Candidate> candidates(std::size_t newest) const;
  void search(std::size_t newest, const Candidate& candidate);
  SurfacePoints neighbourhood(std::size_t centre, std::size_t first, std::size_t last) const;
  void optimise_graph();
  void count_loops();
  double largest_shift() const;
  MapCorrection correction_about(std::size_t newest);

  SlamConfig::LoopClosure config_;
  PoseGraph graph_;
  std::vector<Node> nodes_;
  // Where the front end's map has each keyframe: the graph's poses when it was last rebuilt on
  // them, the front end's own for the keyframes since.
  std::vector<NodePose> in_front_end_;
  std::vector<Eigen::Matrix2d> unseen_;  // add()'s, per keyframe
  std::size_t loops_unoptimised_ = 0;
  LoopCounts counts_;
};

}  // namespace uavslam::backend
