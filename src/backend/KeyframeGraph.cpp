#include "backend/KeyframeGraph.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <set>
#include <string>
#include <utility>

#include "backend/CorrelativeMatcher.hpp"
#include "core/Angles.hpp"

namespace uavslam::backend {
namespace {

// Points this far above or below the keyframe's body are not in its horizontal slice: the floor
// under a UAV, what a tilted scanner sees high on a far wall.
constexpr double kSliceHalfHeight = 0.5;  // m
// The z of a loop is not measured by the 2D search: it keeps the chain's, this loosely held.
constexpr double kLoopHeightSigma = 1.0;  // m
// A new loop within this of the estimate (chi-square, 4 degrees of freedom, 95 %) agrees with it.
constexpr double kAgreeingChi2 = 9.49;
constexpr std::size_t kLoopsPerOptimisation = 10;
// m: a keyframe moved by less than this (under the scans' noise) leaves the front end's map alone.
constexpr double kMinCorrection = 0.01;

Eigen::Matrix3d heading(double yaw) {
  return Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
}

// Into the keyframe's heading frame: the world frame turned by its yaw about the vertical, at its
// position. Roll and pitch stay in the points: the orientation source fixes them.
Vec3 to_node_frame(const NodePose& node, const Vec3& world) {
  return heading(node.yaw).transpose() * (world - node.position);
}

Eigen::Matrix4d diagonal_information(double sigma_xy, double sigma_z, double sigma_yaw) {
  return Eigen::Vector4d(1.0 / (sigma_xy * sigma_xy), 1.0 / (sigma_xy * sigma_xy),
                         1.0 / (sigma_z * sigma_z), 1.0 / (sigma_yaw * sigma_yaw))
      .asDiagonal();
}

// One point per cell of `cell` (the first): the correlative matcher's cost grows with the points,
// and points closer than its grid add nothing.
SurfacePoints thinned(const SurfacePoints& surface, double cell) {
  std::set<std::pair<long, long>> taken;
  SurfacePoints kept;
  for (std::size_t i = 0; i < surface.points.size(); ++i) {
    const Eigen::Vector2d& p = surface.points[i];
    const std::pair<long, long> key{std::lround(std::floor(p.x() / cell)),
                                    std::lround(std::floor(p.y() / cell))};
    if (!taken.insert(key).second) continue;
    kept.points.push_back(p);
    kept.normals.push_back(surface.normals[i]);
  }
  return kept;
}

// How much a blind direction's covariance grew from one keyframe to the next (its positive part:
// a fix in between leaves none).
Eigen::Matrix2d growth(const Eigen::Matrix2d& before, const Eigen::Matrix2d& after) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(after - before);
  return solver.eigenvectors() * solver.eigenvalues().cwiseMax(0.0).asDiagonal() *
         solver.eigenvectors().transpose();
}

}  // namespace

std::string describe(const LoopCounts& loops) {
  return std::to_string(loops.accepted) + " accepted of " + std::to_string(loops.searches) +
         " searched (rejected: " + std::to_string(loops.rejected_score) + " score, " +
         std::to_string(loops.rejected_ambiguous) + " look-alike, " +
         std::to_string(loops.rejected_back_to_back) + " back to back, " +
         std::to_string(loops.rejected_by_graph) + " by the graph), " +
         std::to_string(loops.optimisations) + " optimisations";
}

MapCorrection correction_between(const NodePose& before, const NodePose& after) {
  MapCorrection c;
  c.yaw = wrap_angle(after.yaw - before.yaw);
  c.transform.linear() = heading(c.yaw);
  c.transform.translation() = after.position - heading(c.yaw) * before.position;
  return c;
}

NodePose MapCorrection::operator()(const NodePose& pose) const {
  return {transform * pose.position, wrap_angle(pose.yaw + yaw)};
}

MapCorrection MapCorrection::then(const MapCorrection& next) const {
  return {next.transform * transform, wrap_angle(yaw + next.yaw)};
}

KeyframeGraph::KeyframeGraph(const SlamConfig::LoopClosure& config) : config_(config) {}

// The chain's noise between two successive keyframes (loop_closure.step_*): grows with the
// distance and the turn between them. Where the front end's scans were blind (a corridor's
// axis), the step is what its motion prior carried, and as uncertain as that grew between them
// (unseen_growth, world x-y, turned into `from`'s frame): a loop at the end of a blind stretch
// is searched as wide as the stretch allows, and the optimisation bends the stretch, not the
// steps the scans held.
Constraint KeyframeGraph::step_constraint(const NodePose& from, const NodePose& to,
                                          const Eigen::Matrix2d& unseen_growth) const {
  Constraint c = relative(from, to);
  const double sigma = config_.step_sigma + config_.step_sigma_per_metre * c.translation.norm();
  const double yaw_sigma =
      config_.step_yaw_sigma + config_.step_yaw_sigma_per_radian * std::abs(c.yaw);
  c.information = diagonal_information(sigma, sigma, yaw_sigma);
  if (unseen_growth.trace() > 0.0) {
    const Eigen::Matrix2d turn = heading(from.yaw).topLeftCorner<2, 2>();
    const Eigen::Matrix2d covariance =
        sigma * sigma * Eigen::Matrix2d::Identity() + turn.transpose() * unseen_growth * turn;
    c.information.topLeftCorner<2, 2>() = covariance.inverse();
  }
  return c;
}

std::optional<MapCorrection> KeyframeGraph::add(const NodePose& pose, const Points& points,
                                                const std::vector<Vec3>& normals,
                                                const Eigen::Matrix2d& unseen) {
  Node node;
  if (nodes_.empty()) {
    graph_.add_node(pose);
  } else {
    // The front end's motion since its last keyframe, from where the graph now has that one.
    Constraint step = step_constraint(in_front_end_.back(), pose, growth(unseen_.back(), unseen));
    step.from = nodes_.size() - 1;
    step.to = graph_.add_node(compose(graph_.node(step.from), step));
    graph_.add_constraint(step);
    node.travelled = nodes_.back().travelled + step.translation.norm();
  }
  in_front_end_.push_back(pose);
  unseen_.push_back(unseen);
  for (const Vec3& n : normals) node.normals.push_back(heading(pose.yaw).transpose() * n);
  for (std::size_t i = 0; i < points.size(); ++i) {
    node.points.push_back(to_node_frame(pose, points[i]));
    const Vec3& p = node.points.back();
    node.reach = std::max(node.reach, p.head<2>().norm());
    if (std::abs(p.z()) > kSliceHalfHeight) continue;
    node.slice.points.push_back(p.head<2>());
    node.slice.normals.push_back(normals.size() == points.size()
                                     ? toward_scanner(p.head<2>(), node.normals[i])
                                     : Eigen::Vector2d::Zero());
  }
  nodes_.push_back(std::move(node));

  const std::size_t newest = nodes_.size() - 1;
  const std::size_t loops_before = graph_.constraints().size();
  for (const Candidate& candidate : candidates(newest)) search(newest, candidate);
  // A loop the estimate already agrees with moves nothing: the graph is optimised when one does
  // not, or after kLoopsPerOptimisation that do.
  bool disagrees = false;
  for (std::size_t i = loops_before; i < graph_.constraints().size(); ++i) {
    disagrees = disagrees || graph_.chi2(i) > kAgreeingChi2;
  }
  loops_unoptimised_ += graph_.constraints().size() - loops_before;
  count_loops();
  if (!disagrees && loops_unoptimised_ < kLoopsPerOptimisation) return std::nullopt;
  optimise_graph();
  // The front end's map is rebuilt only when a keyframe's points moved by more than it can see.
  if (largest_shift() < kMinCorrection) return std::nullopt;
  return correction_about(newest);
}

std::optional<MapCorrection> KeyframeGraph::optimise() {
  if (nodes_.empty()) return std::nullopt;
  optimise_graph();
  return correction_about(nodes_.size() - 1);
}

MapCorrection KeyframeGraph::turn_headings(const std::vector<double>& turns) {
  graph_.turn_headings(turns);
  optimise_graph();
  return correction_about(nodes_.size() - 1);
}

void KeyframeGraph::optimise_graph() {
  graph_.optimise();
  ++counts_.optimisations;
  count_loops();
  loops_unoptimised_ = 0;
}

// The loops in the graph, and those it switched off, as they stand now (a loop the estimate
// agrees with is in the graph before any optimisation).
void KeyframeGraph::count_loops() {
  counts_.accepted = 0;
  counts_.rejected_by_graph = 0;
  for (std::size_t i = 0; i < graph_.constraints().size(); ++i) {
    if (graph_.constraints()[i].kind != ConstraintKind::Loop) continue;
    ++(graph_.active()[i] ? counts_.accepted : counts_.rejected_by_graph);
  }
}

// m: the most any keyframe's farthest point moved between the front end's map and the graph.
double KeyframeGraph::largest_shift() const {
  double largest = 0.0;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const NodePose& now = graph_.node(k);
    const NodePose& mapped = in_front_end_[k];
    largest = std::max(largest, (now.position - mapped.position).norm() +
                                    nodes_[k].reach * std::abs(wrap_angle(now.yaw - mapped.yaw)));
  }
  return largest;
}

// The front end's frame onto the graph's about the newest keyframe; the front end's map is then
// the graph's.
MapCorrection KeyframeGraph::correction_about(std::size_t newest) {
  const MapCorrection c = correction_between(in_front_end_[newest], graph_.node(newest));
  in_front_end_ = graph_.nodes();
  return c;
}

// How uncertain each keyframe is relative to the newest, through the graph's best path (loops
// included): Dijkstra over the constraints with each one's variance, first-order propagated:
//   var(v) = min over paths of sum_e ( sigma_e^2 + |p_newest - p_u|^2 sigma_yaw,e^2 )
// (u: the constraint's end nearer the newest; a heading error there turns the rest of the path
// about it, moving the newest by that lever; Olson's Dijkstra projection, in scalars).
std::vector<KeyframeGraph::PathUncertainty> KeyframeGraph::uncertainty_from(
    std::size_t newest) const {
  std::vector<std::vector<std::size_t>> edges(nodes_.size());
  const std::vector<Constraint>& constraints = graph_.constraints();
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    if (!graph_.active()[i]) continue;
    edges[constraints[i].from].push_back(i);
    edges[constraints[i].to].push_back(i);
  }
  std::vector<PathUncertainty> best(nodes_.size());
  std::vector<bool> settled(nodes_.size(), false);
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  best[newest] = {0.0, 0.0};
  queue.push({0.0, newest});
  const Vec3& here = graph_.node(newest).position;
  while (!queue.empty()) {
    const std::size_t u = queue.top().second;
    queue.pop();
    if (settled[u]) continue;
    settled[u] = true;
    const double lever = (graph_.node(u).position - here).squaredNorm();
    for (const std::size_t e : edges[u]) {
      const Constraint& c = constraints[e];
      const std::size_t v = c.from == u ? c.to : c.from;
      const double yaw_variance = 1.0 / c.information(3, 3);
      // Its largest horizontal variance, 1 / the smallest eigenvalue of its x-y information: the
      // scalar stands for both axes.
      const double p = c.information(0, 0);
      const double r = c.information(1, 1);
      const double q = c.information(0, 1);
      const double step_variance =
          1.0 / ((p + r) / 2.0 - std::sqrt((p - r) * (p - r) / 4.0 + q * q));
      const double position = best[u].position + step_variance + lever * yaw_variance;
      if (settled[v] || position >= best[v].position) continue;
      best[v] = {position, best[u].yaw + yaw_variance};
      queue.push({position, v});
    }
  }
  return best;
}

// Older keyframes the estimate puts within 3 sigma of the graph's path to the newest (plus
// min_radius), nearest first, at most max_candidates, no two from the same neighbourhood.
std::vector<KeyframeGraph::Candidate> KeyframeGraph::candidates(std::size_t newest) const {
  const Node& last = nodes_[newest];
  const NodePose& here = graph_.node(newest);
  const std::vector<PathUncertainty> uncertainty = uncertainty_from(newest);
  std::vector<Candidate> all;
  for (std::size_t j = 0; j < newest; ++j) {
    if (last.travelled - nodes_[j].travelled < config_.min_travel) break;  // grows with j
    const PathUncertainty& u = uncertainty[j];
    if (!std::isfinite(u.position)) continue;
    // Placed within what the front end's matching corrects anyway: nothing for a loop to add.
    if (3.0 * std::sqrt(u.position) < config_.known_radius) continue;
    const double radius =
        std::clamp(3.0 * std::sqrt(u.position), config_.min_radius, config_.max_radius);
    const double distance = (graph_.node(j).position - here.position).head<2>().norm();
    if (distance > radius + config_.min_radius) continue;
    const double angular = std::min(M_PI, 3.0 * std::sqrt(u.yaw) + 0.05);
    all.push_back({j, distance, radius, angular});
  }
  std::sort(all.begin(), all.end(),
            [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
  std::vector<Candidate> chosen;
  const auto spread = static_cast<std::size_t>(config_.submap_keyframes);
  for (const Candidate& c : all) {
    const bool near_chosen = std::any_of(chosen.begin(), chosen.end(), [&](const Candidate& o) {
      return std::max(c.keyframe, o.keyframe) - std::min(c.keyframe, o.keyframe) <= spread;
    });
    if (near_chosen) continue;
    chosen.push_back(c);
    if (chosen.size() >= static_cast<std::size_t>(config_.max_candidates)) break;
  }
  return chosen;
}

// The 2D slices of keyframes first..last in keyframe `centre`'s frame, at the graph's poses.
SurfacePoints KeyframeGraph::neighbourhood(std::size_t centre, std::size_t first,
                                           std::size_t last) const {
  const NodePose& origin = graph_.node(centre);
  SurfacePoints surface;
  for (std::size_t k = first; k <= last; ++k) {
    const Constraint seen = relative(origin, graph_.node(k));
    const Eigen::Matrix2d turn = heading(seen.yaw).topLeftCorner<2, 2>();
    const SurfacePoints& slice = nodes_[k].slice;
    for (std::size_t i = 0; i < slice.points.size(); ++i) {
      surface.points.push_back(turn * slice.points[i] + seen.translation.head<2>());
      surface.normals.push_back(turn * slice.normals[i]);
    }
  }
  return surface;
}

// The newest keyframe's neighbourhood (it and the submap_keyframes before it) searched over the
// candidate's (submap_keyframes either side) around where the estimate puts it.
void KeyframeGraph::search(std::size_t newest, const Candidate& candidate) {
  ++counts_.searches;
  const auto spread = static_cast<std::size_t>(config_.submap_keyframes);
  const std::size_t j = candidate.keyframe;
  const SurfacePoints reference =
      neighbourhood(j, j >= spread ? j - spread : 0, std::min(newest - 1, j + spread));
  const SurfacePoints scan =
      thinned(neighbourhood(newest, newest >= spread ? newest - spread : 0, newest),
              2.0 * config_.resolution);
  CorrelativeMatcherConfig matcher_config;
  matcher_config.resolution = config_.resolution;
  matcher_config.ambiguity_radius = config_.ambiguity_radius;
  const CorrelativeMatcher matcher(reference.points, matcher_config);

  const Constraint estimated = relative(graph_.node(j), graph_.node(newest));
  SearchWindow window;
  window.centre =
      Eigen::Vector3d(estimated.translation.x(), estimated.translation.y(), estimated.yaw);
  window.linear = candidate.radius;
  window.angular = candidate.angular;
  const CorrelativeMatch match = matcher.match(scan.points, window, config_.min_score);
  if (!match.found) {
    ++counts_.rejected_score;
    return;
  }
  // A look-alike scoring nearly as well, or a best pose on the slope of a ridge: ambiguous.
  if (match.score - match.second_score < config_.min_score_margin ||
      !matcher.is_peak(scan.points, match.pose)) {
    ++counts_.rejected_ambiguous;
    return;
  }
  // Surfaces laid on each other from their two sides: a wall on the far face of a block, a niche's
  // face on the niche's other face (SurfaceSides).
  const SideCount sides = compare_sides(reference, scan, match.pose, 2.0 * config_.resolution);
  if (sides.opposed_share() > config_.max_opposed_share ||
      sides.weak_opposed_share() > config_.max_opposed_share) {
    ++counts_.rejected_back_to_back;
    return;
  }
  Constraint loop;
  loop.from = j;
  loop.to = newest;
  loop.translation = Vec3(match.pose.x(), match.pose.y(), estimated.translation.z());
  loop.yaw = match.pose.z();
  loop.information =
      diagonal_information(config_.loop_sigma, kLoopHeightSigma, config_.loop_yaw_sigma);
  loop.kind = ConstraintKind::Loop;
  graph_.add_constraint(loop);
}

Points KeyframeGraph::points_in_world(std::size_t keyframe) const {
  const NodePose& at = graph_.node(keyframe);
  const Eigen::Matrix3d turn = heading(at.yaw);
  Points world;
  world.reserve(nodes_[keyframe].points.size());
  for (const Vec3& p : nodes_[keyframe].points) world.push_back(turn * p + at.position);
  return world;
}

std::vector<Vec3> KeyframeGraph::normals_in_world(std::size_t keyframe) const {
  const Eigen::Matrix3d turn = heading(graph_.node(keyframe).yaw);
  std::vector<Vec3> world;
  world.reserve(nodes_[keyframe].normals.size());
  for (const Vec3& n : nodes_[keyframe].normals) world.push_back(turn * n);
  return world;
}

}  // namespace uavslam::backend
