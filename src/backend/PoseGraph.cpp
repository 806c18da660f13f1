#include "backend/PoseGraph.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <ceres/ceres.h>
#include <Eigen/Cholesky>

#include "core/Angles.hpp"

namespace uavslam::backend {
namespace {

// The world frame turned by `yaw` about the vertical, as a rotation of column vectors.
template <typename T>
Eigen::Matrix<T, 3, 3> heading_rotation(const T& yaw) {
  using std::cos;
  using std::sin;
  Eigen::Matrix<T, 3, 3> r = Eigen::Matrix<T, 3, 3>::Identity();
  r(0, 0) = cos(yaw);
  r(0, 1) = -sin(yaw);
  r(1, 0) = sin(yaw);
  r(1, 1) = cos(yaw);
  return r;
}

// An angle wrapped into [-pi, pi), differentiable (ceres' pose_graph_2d example).
template <typename T>
T wrapped(const T& angle) {
  using std::floor;
  const T two_pi(2.0 * M_PI);
  return angle - two_pi * floor((angle + T(M_PI)) / two_pi);
}

// The error of a constraint (4-DoF pose graph, Qin et al. 2018 VINS-Mono eq. 26):
//   e = [ R(yaw_i)^T (p_j - p_i) - t_ij ;  wrap(yaw_j - yaw_i - yaw_ij) ]
template <typename T>
Eigen::Matrix<T, 4, 1> constraint_error(const Constraint& c, const T* p_i, const T* yaw_i,
                                        const T* p_j, const T* yaw_j) {
  const Eigen::Map<const Eigen::Matrix<T, 3, 1>> from(p_i);
  const Eigen::Map<const Eigen::Matrix<T, 3, 1>> to(p_j);
  Eigen::Matrix<T, 4, 1> e;
  e.template head<3>() =
      heading_rotation(*yaw_i).transpose() * (to - from) - c.translation.cast<T>();
  e(3) = wrapped(*yaw_j - *yaw_i - T(c.yaw));
  return e;
}

// The residual Ceres squares: r = U e with U^T U = the information, so |r|^2 = e^T I e.
struct ConstraintResidual {
  Constraint constraint;
  Eigen::Matrix4d sqrt_information;

  template <typename T>
  bool operator()(const T* p_i, const T* yaw_i, const T* p_j, const T* yaw_j, T* out) const {
    Eigen::Map<Eigen::Matrix<T, 4, 1>> residual(out);
    residual = sqrt_information.cast<T>() * constraint_error(constraint, p_i, yaw_i, p_j, yaw_j);
    return true;
  }
};

Eigen::Matrix4d upper_cholesky(const Eigen::Matrix4d& information) {
  const Eigen::LLT<Eigen::Matrix4d> llt(information);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("pose graph: a constraint's information is not positive definite");
  }
  return llt.matrixU();
}

}  // namespace

Constraint relative(const NodePose& from, const NodePose& to) {
  Constraint c;
  c.translation = heading_rotation(from.yaw).transpose() * (to.position - from.position);
  c.yaw = wrap_angle(to.yaw - from.yaw);
  return c;
}

NodePose compose(const NodePose& from, const Constraint& measured) {
  return {from.position + heading_rotation(from.yaw) * measured.translation,
          wrap_angle(from.yaw + measured.yaw)};
}

std::size_t PoseGraph::add_node(const NodePose& pose) {
  nodes_.push_back(pose);
  return nodes_.size() - 1;
}

void PoseGraph::add_constraint(const Constraint& constraint) {
  if (constraint.from >= nodes_.size() || constraint.to >= nodes_.size()) {
    throw std::out_of_range(
        "pose graph: a constraint between nodes " + std::to_string(constraint.from) + " and " +
        std::to_string(constraint.to) + " of a graph of " + std::to_string(nodes_.size()));
  }
  if (constraint.from == constraint.to) {
    throw std::invalid_argument("pose graph: a constraint from node " +
                                std::to_string(constraint.from) + " to itself");
  }
  upper_cholesky(constraint.information);  // refused now rather than inside the solver
  constraints_.push_back(constraint);
  active_.push_back(true);
}

double PoseGraph::chi2(std::size_t i) const {
  const Constraint& c = constraints_.at(i);
  const NodePose& a = nodes_[c.from];
  const NodePose& b = nodes_[c.to];
  const Eigen::Vector4d e =
      constraint_error<double>(c, a.position.data(), &a.yaw, b.position.data(), &b.yaw);
  return e.dot(c.information * e);
}

std::size_t PoseGraph::switch_off_outliers(double threshold) {
  std::size_t switched = 0;
  for (std::size_t i = 0; i < constraints_.size(); ++i) {
    if (active_[i] && constraints_[i].kind == ConstraintKind::Loop && chi2(i) > threshold) {
      active_[i] = false;
      ++switched;
    }
  }
  return switched;
}

void PoseGraph::solve(const PoseGraphOptions& options, OptimisationReport& report) {
  ceres::Problem problem;
  for (std::size_t i = 0; i < constraints_.size(); ++i) {
    if (!active_[i]) continue;
    const Constraint& c = constraints_[i];
    auto* cost = new ceres::AutoDiffCostFunction<ConstraintResidual, 4, 3, 1, 3, 1>(
        new ConstraintResidual{c, upper_cholesky(c.information)});
    ceres::LossFunction* loss =
        c.kind == ConstraintKind::Loop ? new ceres::CauchyLoss(options.loop_loss_scale) : nullptr;
    problem.AddResidualBlock(cost, loss, nodes_[c.from].position.data(), &nodes_[c.from].yaw,
                             nodes_[c.to].position.data(), &nodes_[c.to].yaw);
  }
  if (problem.NumResidualBlocks() == 0) return;
  if (problem.HasParameterBlock(nodes_[0].position.data())) {
    problem.SetParameterBlockConstant(nodes_[0].position.data());
    problem.SetParameterBlockConstant(&nodes_[0].yaw);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options.max_iterations;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (report.iterations == 0) report.initial_cost = summary.initial_cost;
  report.final_cost = summary.final_cost;
  report.iterations += static_cast<int>(summary.iterations.size());
  report.converged = summary.termination_type == ceres::CONVERGENCE;
}

void PoseGraph::turn_headings(const std::vector<double>& turns) {
  if (turns.empty()) throw std::invalid_argument("turn_headings: no turns");
  const auto turn = [&turns](std::size_t node) {
    return turns[std::min(node, turns.size() - 1)] - turns.front();
  };
  for (Constraint& c : constraints_) {
    if (c.kind == ConstraintKind::Sequential) c.yaw = wrap_angle(c.yaw + turn(c.to) - turn(c.from));
  }
  const std::vector<NodePose> before = nodes_;
  for (std::size_t i = 1; i < nodes_.size(); ++i) {
    nodes_[i].position = nodes_[i - 1].position +
                         yaw_rotation(turn(i - 1)) * (before[i].position - before[i - 1].position);
    nodes_[i].yaw = wrap_angle(before[i].yaw + turn(i));
  }
}

OptimisationReport PoseGraph::optimise(const PoseGraphOptions& options) {
  OptimisationReport report;
  solve(options, report);
  // Loops the rest of the graph disagrees with are switched off and the graph solved without them.
  for (int round = 0;
       round < options.max_outlier_rounds && switch_off_outliers(options.outlier_chi2) > 0;
       ++round) {
    solve(options, report);
  }
  for (NodePose& n : nodes_) n.yaw = wrap_angle(n.yaw);
  for (std::size_t i = 0; i < constraints_.size(); ++i) {
    if (constraints_[i].kind != ConstraintKind::Loop) continue;
    ++(active_[i] ? report.loops_active : report.loops_rejected);
  }
  return report;
}

}  // namespace uavslam::backend
