// The occupancy map of the map server: an OctoMap octree (Hornung et al. 2013) into which every
// keyframe's points are ray-cast from the sensor origin. The cells a ray crosses become more
// likely free, the cell it ends in more likely occupied; the snapshot is the pruned tree.
#pragma once

#include <cstdint>
#include <memory>

#include <octomap/OcTree.h>

#include "core/Types.hpp"

namespace uavslam {

struct OccupancyConfig {
  double resolution = 0.1;       // m, the leaf size
  double max_range = -1.0;       // m; a longer ray clears up to here and marks nothing; <= 0: any
  double probability_hit = 0.7;  // OctoMap's defaults
  double probability_miss = 0.4;
  // Inner nodes updated once, when the tree is asked for (OctoMap's lazy evaluation): the same
  // tree, built faster, for a map made in one go (the offline mapper); a live map (the map
  // server) updates them as it goes.
  bool batch = false;
};

class OccupancyOctree {
 public:
  // Throws std::invalid_argument naming the value unless resolution > 0, probability_hit is in
  // (0.5, 1) and probability_miss in (0, 0.5).
  explicit OccupancyOctree(const OccupancyConfig& config);

  // One keyframe: every point is the end of a ray from sensor_origin (OctoMap's
  // insertPointCloud). Returns false and leaves the map unchanged when the keyframe is malformed:
  // no points, or a point or the origin not finite.
  bool insert_keyframe(const Points& points, const Vec3& sensor_origin);

  // The tree, pruned (children with equal occupancy folded into their parent, which loses no
  // information): what a snapshot carries. Inserts already prune as they go; this guarantees it.
  const octomap::OcTree& pruned_tree();
  const octomap::OcTree& tree() const { return *tree_; }

  // Leaves classified occupied (maximum likelihood), counted over the current tree.
  std::uint64_t occupied_leaves() const;
  std::uint64_t points_inserted() const { return points_inserted_; }
  std::uint64_t keyframes_inserted() const { return keyframes_inserted_; }
  // Grows with every inserted keyframe: a snapshot is stale when it was taken at a lower revision.
  std::uint64_t revision() const { return keyframes_inserted_; }

  const OccupancyConfig& config() const { return config_; }

 private:
  OccupancyConfig config_;
  std::unique_ptr<octomap::OcTree> tree_;
  std::uint64_t points_inserted_ = 0;
  std::uint64_t keyframes_inserted_ = 0;
};

// True when the keyframe can be inserted: at least one point, and every point and the origin
// finite.
bool is_well_formed_keyframe(const Points& points, const Vec3& sensor_origin);

}  // namespace uavslam
