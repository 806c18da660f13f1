// A synthetic flight for the back end's tests: 2D worlds of wall segments, what a keyframe sees
// in them, and a front end whose heading drifts.
#pragma once

#include <cmath>
#include <vector>

#include "backend/KeyframeGraph.hpp"

namespace uavslam::backend::test {

struct Segment {
  Eigen::Vector2d a, b;
};

// Walls sampled every 5 cm; what a keyframe at `at` sees: every sample within `range` (no
// occlusion: enough for the graph, which only needs the places to overlap).
inline Points visible(const std::vector<Segment>& walls, const NodePose& at, double range) {
  Points seen;
  for (const Segment& w : walls) {
    const double length = (w.b - w.a).norm();
    for (double s = 0.0; s <= length; s += 0.05) {
      const Eigen::Vector2d p = w.a + (w.b - w.a) * (s / length);
      if ((p - at.position.head<2>()).norm() <= range) seen.emplace_back(p.x(), p.y(), 0.0);
    }
  }
  return seen;
}

// A 30 x 20 m hall with rooms, pillars and an alcove: no two places alike.
inline std::vector<Segment> hall() {
  return {{{0, 0}, {30, 0}},  {{30, 0}, {30, 20}}, {{30, 20}, {0, 20}},  {{0, 20}, {0, 0}},
          {{8, 0}, {8, 6}},   {{8, 6}, {11, 6}},   {{20, 20}, {20, 13}}, {{20, 13}, {24, 13}},
          {{14, 9}, {16, 9}}, {{16, 9}, {16, 11}}, {{16, 11}, {14, 11}}, {{14, 11}, {14, 9}},
          {{4, 14}, {5, 15}}, {{25, 4}, {27, 4}},  {{27, 4}, {27, 7}},   {{0, 9}, {3, 9}},
          {{22, 0}, {22, 2}}, {{10, 17}, {12, 20}}};
}

// A corridor 2 m wide with a door recess every 2 m on both sides: every place like the next.
inline std::vector<Segment> repeating_corridor() {
  std::vector<Segment> walls;
  for (double x = 0.0; x < 60.0; x += 2.0) {
    walls.push_back({{x, 0}, {x + 1.4, 0}});
    walls.push_back({{x + 1.4, 0}, {x + 1.4, -0.3}});
    walls.push_back({{x + 1.4, -0.3}, {x + 2.0, -0.3}});
    walls.push_back({{x + 2.0, -0.3}, {x + 2.0, 0}});
    walls.push_back({{x, 2}, {x + 1.4, 2}});
    walls.push_back({{x + 1.4, 2}, {x + 1.4, 2.3}});
    walls.push_back({{x + 1.4, 2.3}, {x + 2.0, 2.3}});
    walls.push_back({{x + 2.0, 2.3}, {x + 2.0, 2}});
  }
  return walls;
}

// Around the hall's inner loop at 0.5 m steps, and on past the start.
inline std::vector<NodePose> loop_flight() {
  const std::vector<Eigen::Vector2d> corners = {{4, 3},  {26, 3}, {26, 17},
                                                {4, 17}, {4, 3},  {12, 3}};
  std::vector<NodePose> truth;
  for (std::size_t c = 0; c + 1 < corners.size(); ++c) {
    const Eigen::Vector2d leg = corners[c + 1] - corners[c];
    const double yaw = std::atan2(leg.y(), leg.x());
    const int steps = static_cast<int>(std::round(leg.norm() / 0.5));
    for (int i = 0; i < steps; ++i) {
      const Eigen::Vector2d p = corners[c] + leg * (static_cast<double>(i) / steps);
      truth.push_back({Vec3(p.x(), p.y(), 0.0), yaw});
    }
  }
  return truth;
}

// The front end's view: each step measured with a heading bias (a drifting gyro), so the
// keyframes' poses drift; each keyframe's points are placed where its drifted pose puts them.
struct Flown {
  NodePose pose;
  Points points;
};
inline std::vector<Flown> drift(const std::vector<NodePose>& truth,
                                const std::vector<Segment>& walls, double yaw_bias_per_step) {
  std::vector<Flown> flown;
  NodePose estimate = truth[0];
  for (std::size_t k = 0; k < truth.size(); ++k) {
    if (k > 0) {
      Constraint step = relative(truth[k - 1], truth[k]);
      step.yaw += yaw_bias_per_step;
      estimate = compose(estimate, step);
    }
    Points points;
    for (const Vec3& p : visible(walls, truth[k], 10.0)) {
      // Body frame of the true pose, then out through the drifted one.
      const Vec3 body = Eigen::AngleAxisd(-truth[k].yaw, Vec3::UnitZ()) * (p - truth[k].position);
      points.push_back(estimate.position + Eigen::AngleAxisd(estimate.yaw, Vec3::UnitZ()) * body);
    }
    flown.push_back({estimate, points});
  }
  return flown;
}

}  // namespace uavslam::backend::test
