#include "maps/OccupancyOctree.hpp"

#include <stdexcept>
#include <string>

namespace uavslam {
namespace {

void check_config(const OccupancyConfig& c) {
  if (!(c.resolution > 0.0)) {
    throw std::invalid_argument("occupancy resolution must be > 0 m, got " +
                                std::to_string(c.resolution));
  }
  if (!(c.probability_hit > 0.5 && c.probability_hit < 1.0)) {
    throw std::invalid_argument("occupancy probability_hit must be in (0.5, 1), got " +
                                std::to_string(c.probability_hit));
  }
  if (!(c.probability_miss > 0.0 && c.probability_miss < 0.5)) {
    throw std::invalid_argument("occupancy probability_miss must be in (0, 0.5), got " +
                                std::to_string(c.probability_miss));
  }
}

octomap::point3d to_octomap(const Vec3& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

}  // namespace

bool is_well_formed_keyframe(const Points& points, const Vec3& sensor_origin) {
  if (points.empty() || !sensor_origin.allFinite()) return false;
  for (const Vec3& p : points) {
    if (!p.allFinite()) return false;
  }
  return true;
}

OccupancyOctree::OccupancyOctree(const OccupancyConfig& config) : config_(config) {
  check_config(config_);
  tree_ = std::make_unique<octomap::OcTree>(config_.resolution);
  tree_->setProbHit(config_.probability_hit);
  tree_->setProbMiss(config_.probability_miss);
}

bool OccupancyOctree::insert_keyframe(const Points& points, const Vec3& sensor_origin) {
  if (!is_well_formed_keyframe(points, sensor_origin)) return false;
  octomap::Pointcloud cloud;
  cloud.reserve(points.size());
  for (const Vec3& p : points) cloud.push_back(to_octomap(p));
  // A cell hit by several rays of one keyframe is updated once (discretize), so a dense patch
  // of one scan does not count as many independent observations.
  tree_->insertPointCloud(cloud, to_octomap(sensor_origin), config_.max_range,
                          /*lazy_eval=*/config_.batch, /*discretize=*/true);
  points_inserted_ += points.size();
  ++keyframes_inserted_;
  return true;
}

const octomap::OcTree& OccupancyOctree::pruned_tree() {
  if (config_.batch) tree_->updateInnerOccupancy();
  tree_->prune();
  return *tree_;
}

std::uint64_t OccupancyOctree::occupied_leaves() const {
  std::uint64_t count = 0;
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    count += tree_->isNodeOccupied(*it);
  }
  return count;
}

}  // namespace uavslam
