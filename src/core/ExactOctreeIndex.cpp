#include "core/ExactOctreeIndex.hpp"

#include <algorithm>
#include <limits>

namespace uavslam {
namespace {

// Below this size a leaf stops splitting (coincident points would split it forever).
constexpr double kMinHalfSize = 1e-3;

// Squared distance from q to the cube at center with the half size h (0 inside).
double squared_distance_to_cube(const Vec3& q, const Vec3& center, double h) {
  const Vec3 outside = ((q - center).cwiseAbs().array() - h).cwiseMax(0.0).matrix();
  return outside.squaredNorm();
}

}  // namespace

ExactOctreeIndex::ExactOctreeIndex(std::size_t leaf_capacity)
    : leaf_capacity_(std::max<std::size_t>(leaf_capacity, 1)) {}

void ExactOctreeIndex::add_points(const Points& points) {
  for (const Vec3& p : points) {
    grow_root_to_contain(p);
    points_.push_back(p);
    insert(static_cast<std::uint32_t>(points_.size() - 1));
  }
}

// The octree has no fixed bounds: when a point falls outside, a root twice the size is put above.
void ExactOctreeIndex::grow_root_to_contain(const Vec3& p) {
  if (root_ == kNoChild) {
    nodes_.push_back({p, 8.0, {}, {}, true});
    nodes_.back().children.fill(kNoChild);
    root_ = 0;
    return;
  }
  while (((p - nodes_[root_].center).cwiseAbs().array() > nodes_[root_].half_size).any()) {
    const Node& old = nodes_[root_];
    Vec3 toward(p.x() >= old.center.x() ? 1 : -1, p.y() >= old.center.y() ? 1 : -1,
                p.z() >= old.center.z() ? 1 : -1);
    Node bigger{old.center + toward * old.half_size, 2.0 * old.half_size, {}, {}, true};
    bigger.children.fill(kNoChild);
    const int old_octant = octant_of(bigger, old.center);
    // A leaf root keeps its points: the bigger cube becomes the leaf that holds them.
    if (old.leaf) {
      bigger.points = old.points;
      nodes_[root_] = bigger;
      continue;
    }
    bigger.children[old_octant] = root_;
    bigger.leaf = false;
    nodes_.push_back(bigger);
    root_ = static_cast<std::int32_t>(nodes_.size() - 1);
  }
}

int ExactOctreeIndex::octant_of(const Node& node, const Vec3& p) const {
  return (p.x() >= node.center.x() ? 1 : 0) | (p.y() >= node.center.y() ? 2 : 0) |
         (p.z() >= node.center.z() ? 4 : 0);
}

std::int32_t ExactOctreeIndex::make_child(std::int32_t node_index, int octant) {
  const double h = nodes_[node_index].half_size / 2.0;
  const Vec3 offset((octant & 1) ? h : -h, (octant & 2) ? h : -h, (octant & 4) ? h : -h);
  Node child{nodes_[node_index].center + offset, h, {}, {}, true};
  child.children.fill(kNoChild);
  nodes_.push_back(std::move(child));
  const auto child_index = static_cast<std::int32_t>(nodes_.size() - 1);
  nodes_[node_index].children[octant] = child_index;
  return child_index;
}

void ExactOctreeIndex::insert(std::uint32_t point_index) {
  const Vec3& p = points_[point_index];
  std::int32_t node = root_;
  while (!nodes_[node].leaf) {
    const int octant = octant_of(nodes_[node], p);
    const std::int32_t child = nodes_[node].children[octant];
    node = child != kNoChild ? child : make_child(node, octant);
  }
  nodes_[node].points.push_back(point_index);
  if (nodes_[node].points.size() > leaf_capacity_ && nodes_[node].half_size > kMinHalfSize) {
    split(node);
  }
}

void ExactOctreeIndex::split(std::int32_t node_index) {
  std::vector<std::uint32_t> moving;
  moving.swap(nodes_[node_index].points);
  nodes_[node_index].leaf = false;
  for (std::uint32_t i : moving) {
    const int octant = octant_of(nodes_[node_index], points_[i]);
    std::int32_t child = nodes_[node_index].children[octant];
    if (child == kNoChild) child = make_child(node_index, octant);
    nodes_[child].points.push_back(i);
  }
  // A copy: splitting a child appends nodes, which may move nodes_[node_index].
  const std::array<std::int32_t, 8> children = nodes_[node_index].children;
  for (std::int32_t child : children) {
    if (child != kNoChild && nodes_[child].points.size() > leaf_capacity_ &&
        nodes_[child].half_size > kMinHalfSize) {
      split(child);
    }
  }
}

// Branch and bound: the octant holding the query first, then the others nearest first, skipping
// every cube farther away than the best point found so far.
void ExactOctreeIndex::search(std::int32_t node_index, const Vec3& q, Neighbour& best) const {
  const Node& node = nodes_[node_index];
  for (std::uint32_t i : node.points) {
    const double d2 = (points_[i] - q).squaredNorm();
    if (d2 < best.squared_distance) best = {i, d2};
  }
  std::array<std::pair<double, std::int32_t>, 8> order;
  int count = 0;
  for (std::int32_t child : node.children) {
    if (child == kNoChild) continue;
    // Insertion sort: at most eight octants, nearest first.
    std::pair<double, std::int32_t> entry{
        squared_distance_to_cube(q, nodes_[child].center, nodes_[child].half_size), child};
    int k = count++;
    for (; k > 0 && order[k - 1].first > entry.first; --k) order[k] = order[k - 1];
    order[k] = entry;
  }
  for (int k = 0; k < count; ++k) {
    if (order[k].first >= best.squared_distance) break;
    search(order[k].second, q, best);
  }
}

void ExactOctreeIndex::find_nearest(const Points& queries, std::vector<Neighbour>& nearest) const {
  nearest.resize(queries.size());
  if (root_ == kNoChild) return;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    Neighbour best{0, std::numeric_limits<double>::infinity()};
    search(root_, queries[i], best);
    nearest[i] = best;
  }
}

}  // namespace uavslam
