// The pose graph of the back end (issue 18): keyframes as nodes, what is known of the motion
// between two keyframes as constraints, optimised together so that a loop closed at the end of a
// flight corrects the keyframes along it. Nodes are 4-DoF (position and heading): the orientation
// source fixes roll and pitch against gravity, so only these four drift (as in VINS-Mono's
// 4-DoF pose graph). Constraints from the front end's matches are trusted as they are; loop
// constraints go under a robust loss and are switched off when they disagree with the rest
// (a false loop must not bend the map).
#pragma once

#include <cstddef>
#include <vector>

#include "core/Heading.hpp"
#include "core/Types.hpp"

namespace uavslam::backend {

// A node's pose: where the keyframe's body was and its heading about the world's vertical.
struct NodePose {
  Vec3 position = Vec3::Zero();  // m, world frame
  double yaw = 0.0;              // rad
};

// A body pose as a node sees it (its heading; roll and pitch are the orientation source's), and
// back: level, stamped.
inline NodePose node_of(const Pose& pose) {
  return {pose.position, heading_of(pose.orientation)};
}
inline Pose pose_of(const NodePose& node, double stamp) {
  Pose p;
  p.stamp = stamp;
  p.position = node.position;
  p.orientation = yaw_rotation(node.yaw);
  return p;
}

enum class ConstraintKind { Sequential, Loop };

// What is measured of node `to` seen from node `from`: its position in `from`'s heading frame
// (the world frame turned by from.yaw about the vertical) and the heading difference, with the
// information (inverse covariance) of (x, y, z, yaw) in that order.
struct Constraint {
  std::size_t from = 0;
  std::size_t to = 0;
  Vec3 translation = Vec3::Zero();
  double yaw = 0.0;
  Eigen::Matrix4d information = Eigen::Matrix4d::Identity();
  ConstraintKind kind = ConstraintKind::Sequential;
};

// The constraint two poses satisfy exactly: `to` seen from `from`.
Constraint relative(const NodePose& from, const NodePose& to);
// `from` moved by a constraint's measurement: where it puts `to`.
NodePose compose(const NodePose& from, const Constraint& measured);

struct PoseGraphOptions {
  int max_iterations = 50;
  // The loops' robust loss: Cauchy with this scale, in standard deviations of the constraint.
  double loop_loss_scale = 3.0;
  // A loop whose squared error in its own information exceeds this after an optimisation is
  // taken for false and switched off (chi-square of 4 degrees of freedom: 18.47 at 99.9 %).
  double outlier_chi2 = 18.47;
  int max_outlier_rounds = 3;  // re-optimisations at most, each after switching loops off
};

struct OptimisationReport {
  bool converged = false;
  int iterations = 0;  // over all rounds
  double initial_cost = 0.0;
  double final_cost = 0.0;
  std::size_t loops_active = 0;
  std::size_t loops_rejected = 0;  // switched off, this optimisation or an earlier one
};

class PoseGraph {
 public:
  // The first node added is the map's anchor: it never moves.
  std::size_t add_node(const NodePose& pose);
  // Throws std::out_of_range for a node the graph does not have, std::invalid_argument for a
  // constraint from a node to itself or an information that is not positive definite.
  void add_constraint(const Constraint& constraint);

  OptimisationReport optimise(const PoseGraphOptions& options = {});

  // The front end measured the sequential constraints with each node's heading off by -turns[i]
  // (a drifting heading source, learnt since; the first node is the anchor, turns are taken
  // relative to its own). Each such constraint's heading difference takes the change,
  //   yaw_ij += turn_j - turn_i,
  // its translation, measured in node i's frame, stays; the nodes move as the turned steps place
  // them, p_j = p_i + R(turn_i) (p_j - p_i)_before, ready for the next optimisation. Nodes past
  // the end of turns turn with the last. Throws std::invalid_argument for no turns.
  void turn_headings(const std::vector<double>& turns);

  const NodePose& node(std::size_t i) const { return nodes_.at(i); }
  const std::vector<NodePose>& nodes() const { return nodes_; }
  const std::vector<Constraint>& constraints() const { return constraints_; }
  // One per constraint: false once the loop was switched off as an outlier.
  const std::vector<bool>& active() const { return active_; }
  std::size_t size() const { return nodes_.size(); }

  // The squared error of a constraint at the current poses, in its own information.
  double chi2(std::size_t constraint) const;

 private:
  void solve(const PoseGraphOptions& options, OptimisationReport& report);
  std::size_t switch_off_outliers(double threshold);

  std::vector<NodePose> nodes_;
  std::vector<Constraint> constraints_;
  std::vector<bool> active_;
};

}  // namespace uavslam::backend
