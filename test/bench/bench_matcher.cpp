// Benchmarks of the scan matcher (ScanMatcher::match) and of the nearest-neighbour search under it,
// on one thread, with realistic data: world maps made of the demo world's surfaces as the LiDAR
// sees them along the demo flight, and a real scan of that flight as the query.
//
//   BM_MatchScan/<index>/<scan points>/<map points>  one ICP match (SlamConfig defaults) per scan,
//       starting 5 cm off the true position; time per scan (manual timing) plus p50/p99/max
//   BM_NearestNeighbour/<index>/<map points>         one find_nearest over a 216-point scan; recall
//       against brute force
//   BM_AddKeyframe/<index>/<map points>              adding one 216-point keyframe to the map
//
// See README.md next to this file for how to run them and read the results.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/NearestNeighbourIndex.hpp"
#include "core/ScanMatcher.hpp"
#include "core/ScanProjection.hpp"
#include "core/SlamConfig.hpp"
#include "core/Types.hpp"
#include "core/WorldMap.hpp"
#include "core/nearest_neighbour/BruteForceIndex.hpp"
#include "io/ScenarioFile.hpp"
#include "sim/FlightSimulator.hpp"
#include "sim/SampleClock.hpp"

namespace uavslam::bench {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kScenarioPath = UAVSLAM_SOURCE_DIR "/config/scenarios/demo.yaml";
// The query scan: mid-flight, crossing the middle of the room between the two clutter zones.
constexpr double kQueryTime = 70.0;  // s
constexpr int kSubsample = 5;        // the pipeline's every-k-th point (216 of 1080)
// Maps up to this size are made of 216-point keyframes (what the pipeline adds to its map);
// larger maps take every point of a scan.
constexpr std::size_t kLargestKeyframeMap = 100000;
constexpr std::size_t kAddKeyframeMap = 100000;
constexpr int kAddKeyframes = 200;  // keyframes added in BM_AddKeyframe (the map grows by 43 200)
const std::vector<std::size_t> kMapSizes = {10000, 100000, 1000000};

const sim::Scenario& scenario() {
  static const sim::Scenario s = io::load_scenario(kScenarioPath);
  return s;
}

std::uint64_t scans_in_flight() {
  const sim::FlightSimulator flight(scenario());
  return sim::SampleClock(flight.start_time(), flight.end_time(), scenario().lidar.rate_hz).count();
}

// A scan's valid returns in the world frame at the true body pose.
Points to_world(const Scan& scan, const Pose& pose) {
  const ScanGeometry& geometry = *scan.geometry;
  const Eigen::Isometry3d sensor_to_world = pose.isometry() * geometry.mount;
  Points points;
  points.reserve(scan.ranges.size());
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (is_valid_range(r, geometry)) {
      points.push_back(sensor_to_world * (double(r) * geometry.directions[i]));
    }
  }
  return points;
}

// The scan the matcher and the searches are timed with.
struct Query {
  std::uint64_t sequence = 0;
  Vec3 position = Vec3::Zero();  // true body position
  // The matcher's input as the pipeline makes it (SlamConfig defaults: per-axis weights):
  ScanPoints scan_all;         // every valid point, world-oriented, relative to the body origin
  ScanPoints scan_subsampled;  // every 5th of those (216)
  Points world_subsampled;     // scan_subsampled's points at the true position: the NN queries
};

const Query& query() {
  static const Query q = [] {
    sim::FlightSimulator flight(scenario());
    Scan scan;
    while (flight.next_scan(scan)) {
      if (scan.stamp < kQueryTime) continue;
      const Pose pose = flight.ground_truth_at(scan.stamp);
      Query result;
      result.sequence = scan.sequence;
      result.position = pose.position;
      const ProjectedScan projected = project_scan(scan, pose.orientation);
      const bool split_axes = SlamConfig{}.icp.split_axes;
      result.scan_all = weigh_points(projected.points, projected.vertical, split_axes);
      result.scan_subsampled =
          weigh_points(keep_every_kth(projected.points, kSubsample),
                       keep_every_kth(projected.vertical, kSubsample), split_axes);
      result.world_subsampled = result.scan_subsampled.points;
      for (Vec3& p : result.world_subsampled) p += pose.position;
      return result;
    }
    throw std::runtime_error("the demo flight ends before the query time");
  }();
  return q;
}

// The points of the given scans of the flight (every keep-th valid point of each, world frame, at
// the true pose), one entry per scan, in flight order.
std::map<std::uint64_t, Points> fly_and_collect(const std::vector<bool>& wanted, int keep) {
  std::map<std::uint64_t, Points> collected;
  sim::FlightSimulator flight(scenario());
  Scan scan;
  while (flight.next_scan(scan)) {
    if (scan.sequence < wanted.size() && wanted[scan.sequence]) {
      collected[scan.sequence] =
          keep_every_kth(to_world(scan, flight.ground_truth_at(scan.stamp)), keep);
    }
  }
  return collected;
}

// Van der Corput sequence 0, 1/2, 1/4, 3/4, ...: where in its stride each pass of the flight picks.
double phase_of_pass(int pass) {
  double phase = 0.0;
  double bit = 0.5;
  for (int p = pass; p > 0; p /= 2, bit /= 2) phase += (p % 2) * bit;
  return phase;
}

// A world map's points: `keyframes` in the order they are added, `all` concatenated.
struct MapData {
  std::vector<Points> keyframes;
  Points all;
};

// Scans spread evenly over the whole flight (never the query scan), the map's points taken from
// them until `size` is reached; should the flight run short, it is flown again and the scans in
// between are taken.
MapData make_map_data(std::size_t size) {
  const int keep = size <= kLargestKeyframeMap ? kSubsample : 1;
  const std::uint64_t scans = scans_in_flight();
  const double points_per_scan = double(scenario().lidar.beams) / keep;
  MapData data;
  std::vector<bool> used(scans, false);
  used[query().sequence] = true;
  for (int pass = 0; data.all.size() < size; ++pass) {
    if (pass > 64) throw std::runtime_error("the demo flight cannot fill the map");
    const double wanted = std::ceil(double(size - data.all.size()) / points_per_scan);
    const double step = std::max(1.0, double(scans) / wanted);
    std::vector<bool> take(scans, false);
    for (double s = step * phase_of_pass(pass + 1); s < double(scans); s += step) {
      const auto k = static_cast<std::uint64_t>(s);
      if (!used[k]) take[k] = used[k] = true;
    }
    for (auto& [sequence, points] : fly_and_collect(take, keep)) {
      if (data.all.size() >= size) break;
      if (data.all.size() + points.size() > size) points.resize(size - data.all.size());
      data.all.insert(data.all.end(), points.begin(), points.end());
      data.keyframes.push_back(std::move(points));
    }
    if (std::all_of(used.begin(), used.end(), [](bool u) { return u; })) {
      used.assign(scans, false);  // every scan taken: cycle the flight
      used[query().sequence] = true;
    }
  }
  return data;
}

// Built once per size, kept for the whole run.
const MapData& map_data(std::size_t size) {
  static std::map<std::size_t, MapData> cache;
  auto it = cache.find(size);
  if (it == cache.end()) it = cache.emplace(size, make_map_data(size)).first;
  return it->second;
}

// 216-point keyframes of scans of the flight that are in no map (BM_AddKeyframe adds these).
const std::vector<Points>& extra_keyframes() {
  static const std::vector<Points> keyframes = [] {
    const std::uint64_t scans = scans_in_flight();
    std::vector<bool> take(scans, false);
    const double step = double(scans) / kAddKeyframes;
    // Offset from every stride the maps use (those start at half a stride).
    for (double s = step * 0.3; s < double(scans); s += step) take[std::uint64_t(s)] = true;
    take[query().sequence] = false;
    std::vector<Points> result;
    for (auto& [sequence, points] : fly_and_collect(take, kSubsample)) {
      result.push_back(std::move(points));
    }
    return result;
  }();
  return keyframes;
}

// The nearest-neighbour index a benchmark runs on.
struct IndexSpec {
  std::string name;   // as it appears in the benchmark name
  IndexKind kind;     // make_nearest_neighbour_index
  int checks = 32;    // flann only
  bool bulk = false;  // the whole map in one add_points, not keyframe by keyframe
};

std::string key_of(const IndexSpec& spec, std::size_t size) {
  return spec.name + "/" + std::to_string(size);
}

std::unique_ptr<WorldMap> build_world_map(const IndexSpec& spec, const MapData& data) {
  SlamConfig::NearestNeighbour config;  // defaults: 4 trees
  config.index = spec.kind;
  config.flann_checks = spec.checks;
  auto map = std::make_unique<WorldMap>(make_nearest_neighbour_index(config));
  if (spec.bulk) {
    map->add_points(data.all);
  } else {
    // As the pipeline grows its map: one add_points per keyframe.
    for (const Points& keyframe : data.keyframes) map->add_points(keyframe);
  }
  return map;
}

// The world map of the benchmark running; benchmarks on the same index and map are registered
// one after another, so each is built once. Only one is kept: 1M-point FLANN trees are large.
struct BuiltMap {
  std::string key;
  std::unique_ptr<WorldMap> map;
  double build_seconds = 0.0;
};

const BuiltMap& world_map(const IndexSpec& spec, std::size_t size) {
  static BuiltMap current;
  const std::string key = key_of(spec, size);
  if (current.key != key) {
    current.map.reset();
    const MapData& data = map_data(size);
    const auto start = Clock::now();
    current.map = build_world_map(spec, data);
    current.build_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    current.key = key;
  }
  return current;
}

// The exact squared distance from each query to its nearest map point, by brute force.
const std::vector<double>& brute_force_distances(std::size_t size) {
  static std::map<std::size_t, std::vector<double>> cache;
  auto it = cache.find(size);
  if (it == cache.end()) {
    BruteForceIndex brute;
    brute.add_points(map_data(size).all);
    std::vector<Neighbour> nearest;
    brute.find_nearest(query().world_subsampled, nearest);
    std::vector<double> distances;
    for (const Neighbour& n : nearest) distances.push_back(n.squared_distance);
    it = cache.emplace(size, std::move(distances)).first;
  }
  return it->second;
}

// Nearest-rank percentile of the samples (seconds), in microseconds.
double percentile_us(std::vector<double> samples, double fraction) {
  if (samples.empty()) return 0.0;
  std::sort(samples.begin(), samples.end());
  const auto rank = static_cast<std::size_t>(std::ceil(fraction * double(samples.size())));
  return 1e6 * samples[std::min(samples.size(), std::max<std::size_t>(rank, 1)) - 1];
}

void set_latency_counters(benchmark::State& state, const std::vector<double>& samples) {
  state.counters["p50_us"] = percentile_us(samples, 0.50);
  state.counters["p99_us"] = percentile_us(samples, 0.99);
  state.counters["max_us"] = percentile_us(samples, 1.0);
  state.counters["samples"] = double(samples.size());
}

// ICP of one scan against the map, from 5 cm off the true position, as the pipeline runs it.
void BM_MatchScan(benchmark::State& state, const IndexSpec& spec, int scan_points,
                  std::size_t map_points) {
  const BuiltMap& built = world_map(spec, map_points);
  const WorldMap& map = *built.map;
  const Query& q = query();
  const ScanPoints& scan = scan_points == 1080 ? q.scan_all : q.scan_subsampled;
  const Vec3 initial = q.position + Vec3(1.0, 1.0, 1.0).normalized() * 0.05;
  const ScanMatcher matcher(SlamConfig{}.icp);

  std::vector<double> samples;
  samples.reserve(1 << 16);
  ScanOutcome outcome = ScanOutcome::NoCorrespondences;
  Vec3 position = Vec3::Zero();
  for (auto _ : state) {
    const auto start = Clock::now();
    MatchResult result = matcher.match(map, scan, initial);
    const auto end = Clock::now();
    benchmark::DoNotOptimize(result);
    const double seconds = std::chrono::duration<double>(end - start).count();
    state.SetIterationTime(seconds);
    samples.push_back(seconds);
    outcome = result.outcome;
    position = result.position;
  }
  set_latency_counters(state, samples);
  state.counters["scan_points"] = double(scan.points.size());
  state.counters["map_points"] = double(map.size());
  state.counters["accepted"] = outcome == ScanOutcome::Accepted ? 1.0 : 0.0;
  state.counters["pos_err_mm"] = 1e3 * (position - q.position).norm();
}

// One find_nearest of the 216 scan points at the true pose; recall against brute force.
void BM_NearestNeighbour(benchmark::State& state, const IndexSpec& spec, std::size_t map_points) {
  const BuiltMap& built = world_map(spec, map_points);
  const WorldMap& map = *built.map;
  const Points& queries = query().world_subsampled;

  // Accuracy, once, outside the timed loop.
  const std::vector<double>& exact = brute_force_distances(map_points);
  std::vector<Neighbour> nearest;
  map.find_nearest(queries, nearest);
  std::size_t hits = 0;
  double excess = 0.0;
  double max_excess = 0.0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    // Recomputed in double from the point found (FLANN returns float distances).
    const double found = std::sqrt((map.point(nearest[i].index) - queries[i]).squaredNorm());
    const double best = std::sqrt(exact[i]);
    if (std::abs(found - best) <= 1e-9 * best) ++hits;
    excess += found - best;
    max_excess = std::max(max_excess, found - best);
  }

  for (auto _ : state) {
    map.find_nearest(queries, nearest);
    benchmark::DoNotOptimize(nearest.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(queries.size()));
  state.counters["recall"] = double(hits) / double(queries.size());
  state.counters["excess_mm"] = 1e3 * excess / double(queries.size());
  state.counters["max_excess_mm"] = 1e3 * max_excess;
  state.counters["map_points"] = double(map.size());
  state.counters["build_ms"] = 1e3 * built.build_seconds;
}

// Adding one 216-point keyframe to a 100k map, as the pipeline does at every keyframe. The map is
// a fresh one of its own (it grows by kAddKeyframes keyframes), built keyframe by keyframe.
void BM_AddKeyframe(benchmark::State& state, const IndexSpec& spec, std::size_t map_points) {
  const std::unique_ptr<WorldMap> map = build_world_map(spec, map_data(map_points));
  const std::vector<Points>& keyframes = extra_keyframes();
  std::vector<double> samples;
  std::size_t next = 0;
  for (auto _ : state) {
    const Points& keyframe = keyframes[next++ % keyframes.size()];
    const auto start = Clock::now();
    map->add_points(keyframe);
    const auto end = Clock::now();
    const double seconds = std::chrono::duration<double>(end - start).count();
    state.SetIterationTime(seconds);
    samples.push_back(seconds);
  }
  set_latency_counters(state, samples);
  state.counters["map_points_after"] = double(map->size());
}

std::vector<IndexSpec> nearest_neighbour_specs() {
  std::vector<IndexSpec> specs;
  for (int checks : {1, 4, 8, 16, 32, 64, 128, 256}) {
    specs.push_back({"flann_c" + std::to_string(checks), IndexKind::Flann, checks, false});
  }
  specs.push_back({"flann_c32_bulk", IndexKind::Flann, 32, true});
  specs.push_back({"exact", IndexKind::Exact, 32, false});
  specs.push_back({"brute", IndexKind::Brute, 32, true});
  return specs;
}

bool is_matcher_spec(const IndexSpec& spec) {
  return spec.name == "flann_c32" || spec.name == "flann_c32_bulk" || spec.name == "exact";
}

// Ordered by map, then index, so each map and index is built once.
void register_benchmarks() {
  for (std::size_t size : kMapSizes) {
    for (const IndexSpec& spec : nearest_neighbour_specs()) {
      const std::string suffix = key_of(spec, size);
      auto* nn = benchmark::RegisterBenchmark(
          ("BM_NearestNeighbour/" + suffix).c_str(),
          [spec, size](benchmark::State& state) { BM_NearestNeighbour(state, spec, size); });
      nn->Unit(benchmark::kMicrosecond);
      // Brute force over 1M points takes ~0.3 s a search: a few suffice.
      if (spec.kind == IndexKind::Brute && size >= 1000000) nn->Iterations(3);
      if (!is_matcher_spec(spec)) continue;
      for (int scan_points : {216, 1080}) {
        const std::string name = "BM_MatchScan/" + spec.name + "/" + std::to_string(scan_points) +
                                 "/" + std::to_string(size);
        auto* match = benchmark::RegisterBenchmark(
            name.c_str(), [spec, scan_points, size](benchmark::State& state) {
              BM_MatchScan(state, spec, scan_points, size);
            });
        match->Unit(benchmark::kMicrosecond)->UseManualTime();
      }
    }
  }
  for (const IndexSpec& spec : {IndexSpec{"flann_c32", IndexKind::Flann, 32, false},
                                IndexSpec{"exact", IndexKind::Exact, 32, false}}) {
    benchmark::RegisterBenchmark(
        ("BM_AddKeyframe/" + key_of(spec, kAddKeyframeMap)).c_str(),
        [spec](benchmark::State& state) { BM_AddKeyframe(state, spec, kAddKeyframeMap); })
        ->Unit(benchmark::kMicrosecond)
        ->UseManualTime()
        ->Iterations(kAddKeyframes);
  }
}

}  // namespace
}  // namespace uavslam::bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  uavslam::bench::register_benchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
