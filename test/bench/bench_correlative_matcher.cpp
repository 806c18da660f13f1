// Benchmarks of the loop search's correlative matcher (backend::CorrelativeMatcher): building it
// on a reference and one match, as KeyframeGraph::search does, on a synthetic 20 m x 15 m room
// at 5 cm cells.
//
//   BM_CorrelativeMatch/found    a +-2 m, +-0.5 rad window holding the scan's true pose
//   BM_CorrelativeMatch/nothing  a +-6 m, +-pi window and a scan of another place: nothing
//                                scores min_score 0.55 (the common, expensive case)
//
// Counters: score (best, or 0), candidates (nodes whose bound was computed), points (reference).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "backend/CorrelativeMatcher.hpp"
#include "unit/backend/Walls2d.hpp"

namespace uavslam::bench {
namespace {

using backend::CorrelativeMatch;
using backend::CorrelativeMatcher;
using backend::CorrelativeMatcherConfig;
using backend::SearchWindow;
using backend::test::add_box;
using backend::test::add_wall;
using backend::test::Points2;

constexpr double kMinScore = 0.55;  // KeyframeGraph's default

// A 20 m x 15 m room with partitions and boxes placed without symmetry.
Points2 room() {
  Points2 p;
  add_box(p, {0.013, 0.007}, {20.013, 15.007});
  add_wall(p, {7.013, 15.007}, {7.013, 10.5});
  add_wall(p, {13.5, 0.007}, {13.5, 5.2});
  add_wall(p, {13.5, 8.0}, {20.013, 8.0});
  add_box(p, {2.1, 1.7}, {3.4, 2.5});
  add_box(p, {9.2, 6.1}, {10.9, 6.6});
  add_box(p, {16.3, 10.2}, {16.9, 13.1});
  add_box(p, {4.4, 11.6}, {5.0, 12.0});
  add_box(p, {17.5, 2.0}, {18.6, 3.3});
  return p;
}

// Another place: a 12 m x 4 m hall with pillars every 3 m.
Points2 elsewhere() {
  Points2 p;
  add_box(p, {0.0, 0.0}, {12.0, 4.0});
  for (int k = 1; k < 4; ++k) add_box(p, {3.0 * k - 0.2, 1.8}, {3.0 * k + 0.2, 2.2});
  return p;
}

// The points within `range` of `pose` in its frame, moved along their rays by 1 cm noise and
// thinned to one per 0.1 m cell (KeyframeGraph::search's query).
Points2 seen_from(const Points2& world, const Eigen::Vector3d& pose, double range) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  const Eigen::Rotation2Dd turn(pose.z());
  Points2 scan;
  std::vector<std::pair<long, long>> taken;
  for (const auto& p : world) {
    const Eigen::Vector2d local = turn.inverse() * (p - pose.head<2>());
    if (local.norm() > range || local.norm() < 1e-6) continue;
    const std::pair<long, long> key{std::lround(std::floor(local.x() / 0.1)),
                                    std::lround(std::floor(local.y() / 0.1))};
    bool seen = false;
    for (const auto& t : taken) seen = seen || t == key;
    if (seen) continue;
    taken.push_back(key);
    scan.push_back(local + noise(rng) * local.normalized());
  }
  return scan;
}

void run(benchmark::State& state, const Points2& reference, const Points2& scan,
         const SearchWindow& window, bool expect_found) {
  const CorrelativeMatcherConfig config;
  CorrelativeMatch m;
  for (auto _ : state) {
    const CorrelativeMatcher matcher(reference, config);
    m = matcher.match(scan, window, kMinScore);
    benchmark::DoNotOptimize(m);
  }
  if (m.found != expect_found) state.SkipWithError("unexpected result");
  state.counters["score"] = m.score;
  state.counters["second"] = m.second_score;
  state.counters["candidates"] = static_cast<double>(m.candidates_scored);
  state.counters["points"] = static_cast<double>(reference.size());
  state.counters["scan"] = static_cast<double>(scan.size());
}

void BM_CorrelativeMatch_found(benchmark::State& state) {
  static const Points2 reference = room();
  const Eigen::Vector3d truth(11.37, 7.81, 0.23);
  static const Points2 scan = seen_from(reference, truth, 10.0);
  SearchWindow window;
  window.centre = truth + Eigen::Vector3d(-1.21, 0.93, -0.31);
  window.linear = 2.0;
  window.angular = 0.5;
  run(state, reference, scan, window, true);
}

void BM_CorrelativeMatch_nothing(benchmark::State& state) {
  static const Points2 reference = room();
  static const Points2 scan = seen_from(elsewhere(), Eigen::Vector3d(6.1, 2.05, 0.4), 10.0);
  SearchWindow window;
  window.centre = Eigen::Vector3d(10.0, 7.5, 0.0);
  window.linear = 6.0;
  window.angular = M_PI;
  run(state, reference, scan, window, false);
}

BENCHMARK(BM_CorrelativeMatch_found)
    ->Name("BM_CorrelativeMatch/found")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CorrelativeMatch_nothing)
    ->Name("BM_CorrelativeMatch/nothing")
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace uavslam::bench

BENCHMARK_MAIN();
