// 2D scenes for the correlative matcher's tests and benchmark: walls and boxes as points.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

namespace uavslam::backend::test {

using Points2 = std::vector<Eigen::Vector2d>;

// Points every `spacing` along the segment from a to b.
inline void add_wall(Points2& points, Eigen::Vector2d a, Eigen::Vector2d b,
                     double spacing = 0.025) {
  const int n = static_cast<int>(std::ceil((b - a).norm() / spacing));
  for (int i = 0; i <= n; ++i) points.push_back(a + (b - a) * (static_cast<double>(i) / n));
}

inline void add_box(Points2& points, Eigen::Vector2d lo, Eigen::Vector2d hi) {
  add_wall(points, lo, {hi.x(), lo.y()});
  add_wall(points, {hi.x(), lo.y()}, hi);
  add_wall(points, hi, {lo.x(), hi.y()});
  add_wall(points, {lo.x(), hi.y()}, lo);
}

}  // namespace uavslam::backend::test
