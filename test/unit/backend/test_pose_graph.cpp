#include "backend/PoseGraph.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace uavslam::backend {
namespace {

// Information of a constraint with these standard deviations (m, rad).
Eigen::Matrix4d information(double sigma_position, double sigma_yaw) {
  Eigen::Vector4d variances(sigma_position * sigma_position, sigma_position * sigma_position,
                            sigma_position * sigma_position, sigma_yaw * sigma_yaw);
  return variances.cwiseInverse().asDiagonal();
}

// A loop from node `from` to node `to` measuring what the truth says of `seen_from` and `seen`
// (the true loop: the same nodes), with the confidence of a good match.
Constraint loop(std::size_t from, std::size_t to, const NodePose& seen_from, const NodePose& seen) {
  Constraint c = relative(seen_from, seen);
  c.from = from;
  c.to = to;
  c.kind = ConstraintKind::Loop;
  c.information = information(0.02, 0.01);
  return c;
}

// A square flight of four 10 m legs at 1 m steps, turning 90 degrees at each corner, back
// where it started: the last node is the first place again.
std::vector<NodePose> square_flight() {
  std::vector<NodePose> truth;
  NodePose pose;
  for (int leg = 0; leg < 4; ++leg) {
    for (int step = 0; step < 10; ++step) {
      truth.push_back(pose);
      Constraint forward;
      forward.translation = Vec3(1.0, 0.0, 0.02 * (leg % 2 == 0 ? 1 : -1));
      forward.yaw = step == 9 ? M_PI / 2 : 0.0;
      pose = compose(pose, forward);
    }
  }
  truth.push_back(pose);
  return truth;
}

double position_error(const PoseGraph& graph, const std::vector<NodePose>& truth) {
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    worst = std::max(worst, (graph.node(i).position - truth[i].position).norm());
  }
  return worst;
}

// The front end's chain: each step measured with a small heading bias, as a drifting gyro
// gives, and noise; the nodes start where the chain puts them.
PoseGraph drifted_chain(const std::vector<NodePose>& truth, double yaw_bias_per_step) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.005);
  PoseGraph graph;
  graph.add_node(truth[0]);
  for (std::size_t i = 1; i < truth.size(); ++i) {
    Constraint step = relative(truth[i - 1], truth[i]);
    step.from = i - 1;
    step.to = i;
    step.translation += Vec3(noise(rng), noise(rng), noise(rng));
    step.yaw += yaw_bias_per_step + noise(rng) * 0.1;
    step.information = information(0.01, 0.005);
    graph.add_node(compose(graph.node(i - 1), step));
    graph.add_constraint(step);
  }
  return graph;
}

TEST(PoseGraphTest, RelativeAndComposeAreInverse) {
  const NodePose a{Vec3(1.0, -2.0, 0.5), 0.7};
  const NodePose b{Vec3(-3.0, 4.0, 1.5), -2.9};
  const NodePose back = compose(a, relative(a, b));
  EXPECT_NEAR((back.position - b.position).norm(), 0.0, 1e-12);
  EXPECT_NEAR(back.yaw, b.yaw, 1e-12);
  // Seen from a node turned a quarter left, a point ahead in the world's y is ahead in x.
  const Constraint ahead = relative({Vec3::Zero(), M_PI / 2}, {Vec3(0.0, 2.0, 0.0), M_PI / 2});
  EXPECT_NEAR(ahead.translation.x(), 2.0, 1e-12);
  EXPECT_NEAR(ahead.translation.y(), 0.0, 1e-12);
}

TEST(PoseGraphTest, AConsistentChainIsLeftWhereItIs) {
  const std::vector<NodePose> truth = square_flight();
  PoseGraph graph = drifted_chain(truth, 0.0);
  const std::vector<NodePose> before = graph.nodes();
  const OptimisationReport report = graph.optimise();
  EXPECT_TRUE(report.converged);
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_NEAR((graph.node(i).position - before[i].position).norm(), 0.0, 1e-6) << i;
  }
}

TEST(PoseGraphTest, ClosingTheLoopRemovesTheDrift) {
  const std::vector<NodePose> truth = square_flight();
  PoseGraph graph = drifted_chain(truth, 0.004);  // 0.16 rad over the flight
  const double drifted = position_error(graph, truth);
  ASSERT_GT(drifted, 1.0) << "the chain must have drifted for the test to mean anything";

  graph.add_constraint(loop(truth.size() - 1, 0, truth.back(), truth[0]));
  const OptimisationReport report = graph.optimise();

  EXPECT_EQ(report.loops_active, 1u);
  EXPECT_EQ(report.loops_rejected, 0u);
  EXPECT_LT(report.final_cost, report.initial_cost);
  EXPECT_LT(position_error(graph, truth), 0.15 * drifted);
  EXPECT_NEAR((graph.node(truth.size() - 1).position - truth.back().position).norm(), 0.0, 0.05);
  // The anchor did not move.
  EXPECT_EQ(graph.node(0).position, truth[0].position);
  EXPECT_EQ(graph.node(0).yaw, truth[0].yaw);
}

TEST(PoseGraphTest, AFalseLoopDoesNotBendTheMap) {
  const std::vector<NodePose> truth = square_flight();
  PoseGraph graph = drifted_chain(truth, 0.0);
  const std::vector<NodePose> before = graph.nodes();
  // Node 15 (middle of the second leg) claimed to be where node 35 is, 10 m away, with the
  // confidence of a good match: a look-alike corridor.
  // The measurement of node 15's place, given to node 5.
  graph.add_constraint(loop(35, 5, truth[35], truth[15]));
  const OptimisationReport report = graph.optimise();

  EXPECT_EQ(report.loops_rejected, 1u);
  EXPECT_FALSE(graph.active().back());
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_NEAR((graph.node(i).position - before[i].position).norm(), 0.0, 0.01) << i;
  }
}

TEST(PoseGraphTest, ALookAlikeOneDoorAlongIsSwitchedOff) {
  // The subtle false loop: node 5 matched to node 35's place as if the flight were a metre
  // further along (a corridor whose doors repeat every metre).
  const std::vector<NodePose> truth = square_flight();
  PoseGraph graph = drifted_chain(truth, 0.0);
  const std::vector<NodePose> before = graph.nodes();
  Constraint wrong = loop(35, 5, truth[35], truth[5]);
  wrong.translation += Vec3(1.0, 0.0, 0.0);
  graph.add_constraint(wrong);
  const OptimisationReport report = graph.optimise();

  EXPECT_EQ(report.loops_rejected, 1u);
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_NEAR((graph.node(i).position - before[i].position).norm(), 0.0, 0.01) << i;
  }
}

TEST(PoseGraphTest, ATrueLoopSurvivesBesideAFalseOne) {
  const std::vector<NodePose> truth = square_flight();
  PoseGraph graph = drifted_chain(truth, 0.004);
  const double drifted = position_error(graph, truth);
  graph.add_constraint(loop(truth.size() - 1, 0, truth.back(), truth[0]));
  graph.add_constraint(loop(20, 10, truth[30], truth[10]));  // node 30's place, given to 20
  const OptimisationReport report = graph.optimise();

  EXPECT_EQ(report.loops_active, 1u);
  EXPECT_EQ(report.loops_rejected, 1u);
  EXPECT_TRUE(graph.active()[graph.active().size() - 2]);
  EXPECT_LT(position_error(graph, truth), 0.15 * drifted);
}

TEST(PoseGraphTest, RefusesConstraintsItCannotHold) {
  PoseGraph graph;
  graph.add_node({});
  graph.add_node({Vec3(1.0, 0.0, 0.0), 0.0});
  Constraint c;
  c.from = 0;
  c.to = 2;
  EXPECT_THROW(graph.add_constraint(c), std::out_of_range);
  c.to = 0;
  EXPECT_THROW(graph.add_constraint(c), std::invalid_argument);
  c.to = 1;
  c.information = Eigen::Matrix4d::Zero();
  EXPECT_THROW(graph.add_constraint(c), std::invalid_argument);
  EXPECT_TRUE(graph.constraints().empty());
}

// The chain's drift learnt afterwards (a gyro bias the heading checks found): the nodes' headings
// turned back by it, each step keeps what it measured in its own node's frame, and the chain is
// straight again without a loop; the anchor stays and the optimisation has nothing left to do.
TEST(PoseGraphTest, ADriftLearntAfterwardsStraightensTheChain) {
  const std::vector<NodePose> truth = square_flight();
  const double bias = 0.004;  // rad per step
  PoseGraph graph = drifted_chain(truth, bias);
  const double drifted = position_error(graph, truth);
  ASSERT_GT(drifted, 1.0) << "the chain must have drifted for the test to mean anything";
  std::vector<double> turns;
  for (std::size_t i = 0; i < truth.size(); ++i) turns.push_back(-bias * double(i));

  graph.turn_headings(turns);

  EXPECT_LT(position_error(graph, truth), 0.1 * drifted);
  EXPECT_NEAR(graph.node(truth.size() - 1).yaw, truth.back().yaw, 0.01);
  EXPECT_EQ(graph.node(0).position, truth[0].position);
  const std::vector<NodePose> turned = graph.nodes();
  EXPECT_TRUE(graph.optimise().converged);
  for (std::size_t i = 0; i < turned.size(); ++i) {
    EXPECT_NEAR((graph.node(i).position - turned[i].position).norm(), 0.0, 1e-6) << i;
  }
  EXPECT_THROW(graph.turn_headings({}), std::invalid_argument);
}

TEST(PoseGraphTest, HeadingsComeBackWrapped) {
  PoseGraph graph;
  graph.add_node({Vec3::Zero(), 3.0});
  Constraint turn = relative({Vec3::Zero(), 3.0}, {Vec3(1.0, 0.0, 0.0), -3.0});
  turn.from = 0;
  turn.to = graph.add_node({Vec3(1.0, 0.0, 0.0), 3.1});  // a start 0.18 rad off, across pi
  graph.add_constraint(turn);
  graph.optimise();
  EXPECT_NEAR(graph.node(1).yaw, -3.0, 1e-6);
}

}  // namespace
}  // namespace uavslam::backend
