#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "maps/OccupancyOctree.hpp"

namespace uavslam {
namespace {

enum class Cell { Unknown, Free, Occupied };

Cell cell_at(const octomap::OcTree& tree, const Vec3& p) {
  const octomap::OcTreeNode* node = tree.search(p.x(), p.y(), p.z());
  if (node == nullptr) return Cell::Unknown;
  return tree.isNodeOccupied(node) ? Cell::Occupied : Cell::Free;
}

// Every known leaf's centre and whether it is occupied: the map's maximum-likelihood content.
std::map<std::tuple<float, float, float>, bool> classification(const octomap::OcTree& tree) {
  std::map<std::tuple<float, float, float>, bool> cells;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    cells[{it.getX(), it.getY(), it.getZ()}] = tree.isNodeOccupied(*it);
  }
  return cells;
}

// Cell centres of a 0.1 m grid sit at odd multiples of 0.05 m: points placed there are far from
// any cell border, so float rounding cannot move them into a neighbour.
const Vec3 kOrigin{0.05, 0.05, 0.05};

// A wall at x = 2.05 seen from the origin: 21 points 0.1 m apart along y.
Points wall() {
  Points points;
  for (int i = -10; i <= 10; ++i) points.emplace_back(2.05, 0.05 + 0.1 * i, 0.05);
  return points;
}

TEST(OccupancyOctree, ARayMarksItsEndOccupiedAndTheCellsAlongItFree) {
  OccupancyOctree map(OccupancyConfig{});
  ASSERT_TRUE(map.insert_keyframe({Vec3(2.05, 0.05, 0.05)}, kOrigin));
  const octomap::OcTree& tree = map.tree();
  EXPECT_EQ(cell_at(tree, {2.05, 0.05, 0.05}), Cell::Occupied);
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(cell_at(tree, {0.05 + 0.1 * i, 0.05, 0.05}), Cell::Free) << "cell " << i;
  }
  EXPECT_EQ(cell_at(tree, {2.15, 0.05, 0.05}), Cell::Unknown) << "behind the wall";
  EXPECT_EQ(cell_at(tree, {1.05, 0.55, 0.05}), Cell::Unknown) << "beside the ray";
  EXPECT_EQ(map.occupied_leaves(), 1u);
}

TEST(OccupancyOctree, TheLeafSizeIsTheConfiguredResolution) {
  OccupancyConfig config;
  config.resolution = 0.25;
  OccupancyOctree map(config);
  ASSERT_TRUE(map.insert_keyframe({Vec3(2.0, 0.1, 0.1)}, Vec3(0.1, 0.1, 0.1)));
  EXPECT_DOUBLE_EQ(map.tree().getResolution(), 0.25);
  std::size_t occupied = 0;
  for (auto it = map.tree().begin_leafs(), end = map.tree().end_leafs(); it != end; ++it) {
    if (!map.tree().isNodeOccupied(*it)) continue;
    ++occupied;
    EXPECT_DOUBLE_EQ(it.getSize(), 0.25);
    EXPECT_NEAR(it.getX(), 2.125, 1e-6);  // the 0.25 m cell [2.0, 2.25)
  }
  EXPECT_EQ(occupied, 1u);
}

TEST(OccupancyOctree, APointBeyondMaxRangeClearsTheRayButMarksNothing) {
  OccupancyConfig config;
  config.max_range = 1.0;
  OccupancyOctree map(config);
  ASSERT_TRUE(map.insert_keyframe({Vec3(3.05, 0.05, 0.05)}, kOrigin));
  const octomap::OcTree& tree = map.tree();
  EXPECT_EQ(map.occupied_leaves(), 0u);
  EXPECT_EQ(cell_at(tree, {3.05, 0.05, 0.05}), Cell::Unknown);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(cell_at(tree, {0.05 + 0.1 * i, 0.05, 0.05}), Cell::Free) << "cell " << i;
  }
  EXPECT_EQ(cell_at(tree, {2.05, 0.05, 0.05}), Cell::Unknown) << "past the range";
}

TEST(OccupancyOctree, APointWithinMaxRangeIsStillMarked) {
  OccupancyConfig config;
  config.max_range = 5.0;
  OccupancyOctree map(config);
  ASSERT_TRUE(map.insert_keyframe({Vec3(3.05, 0.05, 0.05)}, kOrigin));
  EXPECT_EQ(cell_at(map.tree(), {3.05, 0.05, 0.05}), Cell::Occupied);
}

TEST(OccupancyOctree, ReinsertingAKeyframeKeepsEveryCellsClassification) {
  OccupancyOctree map(OccupancyConfig{});
  ASSERT_TRUE(map.insert_keyframe(wall(), kOrigin));
  const auto once = classification(map.pruned_tree());
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(map.insert_keyframe(wall(), kOrigin));
  EXPECT_EQ(classification(map.pruned_tree()), once);
  EXPECT_EQ(map.occupied_leaves(), 21u);
}

TEST(OccupancyOctree, RaysThroughAnOccupiedCellClearItOverTime) {
  // A cell seen occupied once, then crossed by many rays: the misses outweigh the single hit.
  OccupancyOctree map(OccupancyConfig{});
  ASSERT_TRUE(map.insert_keyframe({Vec3(1.05, 0.05, 0.05)}, kOrigin));
  ASSERT_EQ(cell_at(map.tree(), {1.05, 0.05, 0.05}), Cell::Occupied);
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(map.insert_keyframe({Vec3(2.05, 0.05, 0.05)}, kOrigin));
  EXPECT_EQ(cell_at(map.tree(), {1.05, 0.05, 0.05}), Cell::Free);
}

TEST(OccupancyOctree, TheSnapshotFoldsUniformSpaceAndKeepsEveryCellsClassification) {
  // A closed box room seen from inside: its free inside folds into nodes bigger than a leaf.
  OccupancyOctree map(OccupancyConfig{});
  Points room;
  for (int i = -15; i <= 15; ++i) {
    for (int k = -15; k <= 15; ++k) {
      const double a = 0.05 + 0.1 * i;
      const double b = 0.05 + 0.1 * k;
      room.insert(room.end(), {{1.55, a, b}, {-1.45, a, b}, {a, 1.55, b}, {a, -1.45, b}});
    }
  }
  ASSERT_TRUE(map.insert_keyframe(room, kOrigin));
  const octomap::OcTree& pruned = map.pruned_tree();
  octomap::OcTree unfolded(pruned);
  unfolded.expand();
  std::size_t folded_leaves = 0;
  for (auto it = pruned.begin_leafs(), end = pruned.end_leafs(); it != end; ++it) {
    folded_leaves += it.getSize() > pruned.getResolution();
  }
  EXPECT_GT(folded_leaves, 0u);
  EXPECT_LT(pruned.getNumLeafNodes(), unfolded.getNumLeafNodes());
  for (auto it = unfolded.begin_leafs(), end = unfolded.end_leafs(); it != end; ++it) {
    const Vec3 p(it.getX(), it.getY(), it.getZ());
    ASSERT_EQ(cell_at(pruned, p), unfolded.isNodeOccupied(*it) ? Cell::Occupied : Cell::Free)
        << p.transpose();
  }
}

// Batch building (the offline mapper's) updates the inner nodes once at the end: the same tree,
// byte for byte, as updating them with every keyframe.
TEST(OccupancyOctree, BuildingInABatchGivesTheSameTree) {
  OccupancyConfig live_config;
  OccupancyConfig batch_config;
  batch_config.batch = true;
  OccupancyOctree live(live_config);
  OccupancyOctree batch(batch_config);
  for (int k = 0; k < 12; ++k) {
    Points keyframe = wall();
    for (Vec3& p : keyframe) p += Vec3(0.03 * k, 0.0, 0.02 * (k % 3));
    keyframe.push_back(Vec3(1.0 + 0.2 * k, -1.5, 0.3));
    const Vec3 origin(0.05 * k, 0.0, 0.1);
    ASSERT_TRUE(live.insert_keyframe(keyframe, origin));
    ASSERT_TRUE(batch.insert_keyframe(keyframe, origin));
  }
  std::ostringstream live_bytes, batch_bytes;
  ASSERT_TRUE(live.pruned_tree().writeBinaryConst(live_bytes));
  ASSERT_TRUE(batch.pruned_tree().writeBinaryConst(batch_bytes));
  EXPECT_GT(live.occupied_leaves(), 0u);
  EXPECT_EQ(batch.occupied_leaves(), live.occupied_leaves());
  EXPECT_EQ(batch_bytes.str(), live_bytes.str());
  // The inner nodes too (what a coarser query reads), which the binary file does not carry.
  for (const Vec3& p : wall()) {
    for (unsigned depth : {10u, 13u, 15u}) {
      const octomap::OcTreeNode* a = live.tree().search(p.x(), p.y(), p.z(), depth);
      const octomap::OcTreeNode* b = batch.tree().search(p.x(), p.y(), p.z(), depth);
      ASSERT_TRUE(a && b);
      EXPECT_EQ(a->getLogOdds(), b->getLogOdds()) << "depth " << depth;
    }
  }
}

TEST(OccupancyOctree, CountsPointsAndKeyframes) {
  OccupancyOctree map(OccupancyConfig{});
  EXPECT_EQ(map.revision(), 0u);
  ASSERT_TRUE(map.insert_keyframe(wall(), kOrigin));
  ASSERT_TRUE(map.insert_keyframe({Vec3(0.05, 2.05, 0.05)}, kOrigin));
  EXPECT_EQ(map.points_inserted(), 22u);
  EXPECT_EQ(map.keyframes_inserted(), 2u);
  EXPECT_EQ(map.revision(), 2u);
  EXPECT_EQ(map.occupied_leaves(), 22u);
}

TEST(OccupancyOctree, AMalformedKeyframeIsRefusedAndChangesNothing) {
  OccupancyOctree map(OccupancyConfig{});
  ASSERT_TRUE(map.insert_keyframe(wall(), kOrigin));
  const auto before = classification(map.tree());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  Points with_nan = wall();
  with_nan[3].y() = nan;
  EXPECT_FALSE(map.insert_keyframe({}, kOrigin));
  EXPECT_FALSE(map.insert_keyframe(with_nan, kOrigin));
  EXPECT_FALSE(map.insert_keyframe({Vec3(inf, 0.0, 0.0)}, kOrigin));
  EXPECT_FALSE(map.insert_keyframe(wall(), Vec3(0.0, nan, 0.0)));
  EXPECT_EQ(classification(map.tree()), before);
  EXPECT_EQ(map.keyframes_inserted(), 1u);
  EXPECT_EQ(map.points_inserted(), 21u);
}

TEST(OccupancyOctree, ABadConfigIsRefusedWithItsValue) {
  OccupancyConfig zero_resolution;
  zero_resolution.resolution = 0.0;
  OccupancyConfig weak_hit;
  weak_hit.probability_hit = 0.5;
  OccupancyConfig strong_miss;
  strong_miss.probability_miss = 0.6;
  EXPECT_THROW(OccupancyOctree{zero_resolution}, std::invalid_argument);
  EXPECT_THROW(OccupancyOctree{weak_hit}, std::invalid_argument);
  EXPECT_THROW(OccupancyOctree{strong_miss}, std::invalid_argument);
  try {
    OccupancyOctree map(strong_miss);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("probability_miss"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("0.6"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace uavslam
