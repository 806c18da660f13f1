// The ground station's map outputs: PNG files, the top-down picture of an octree with the flight
// path, and the octree as .bt and as occupied-cell centres.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/OctreeFile.hpp"
#include "io/PngFile.hpp"
#include "io/TopDownMapImage.hpp"

namespace uavslam::io {
namespace {

using testing::HasSubstr;

constexpr double kResolution = 0.1;
const Rgb kWhite{255, 255, 255};
const Rgb kFreeGrey{225, 225, 225};
const Rgb kStartGreen{30, 170, 60};

class MapPictureTest : public testing::Test {
 protected:
  ~MapPictureTest() override {
    for (const std::string& path : paths_) std::remove(path.c_str());
  }
  std::string temp_path(const std::string& name) {
    const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
    paths_.push_back(testing::TempDir() + "uavslam_" + test->name() + "_" + name);
    return paths_.back();
  }

 private:
  std::vector<std::string> paths_;
};

// A room corner: a wall along y at x = 2.05 (cells 0..9 in y, 0..19 in z, 20 cells high), a box
// one cell high at (0.55, 1.55, 0.05), free cells along y = 0.55 from x = 0.05 to 1.95.
octomap::OcTree small_map() {
  octomap::OcTree tree(kResolution);
  for (int j = 0; j < 10; ++j) {
    for (int k = 0; k < 20; ++k) tree.updateNode(2.05, 0.05 + 0.1 * j, 0.05 + 0.1 * k, true);
  }
  tree.updateNode(0.55, 1.55, 0.05, true);
  for (int i = 0; i < 20; ++i) tree.updateNode(0.05 + 0.1 * i, 0.55, 1.05, false);
  tree.updateInnerOccupancy();
  return tree;
}

std::vector<Pose> path_along_y_equals_one() {
  std::vector<Pose> path(3);
  path[0].position = {0.2, 1.0, 1.0};
  path[1].position = {1.0, 1.0, 1.0};
  path[2].position = {1.6, 1.0, 1.0};
  return path;
}

TEST_F(MapPictureTest, PngRoundTripKeepsSizeAndPixels) {
  RgbImage image(7, 3);
  image.set(0, 0, {1, 2, 3});
  image.set(6, 2, {250, 128, 0});
  const std::string path = temp_path("round.png");
  write_png(path, image);
  const RgbImage back = read_png(path);
  ASSERT_EQ(back.width(), 7);
  ASSERT_EQ(back.height(), 3);
  EXPECT_EQ(back.bytes(), image.bytes());
}

TEST_F(MapPictureTest, PngToAMissingDirectoryIsAFileErrorNamingThePath) {
  const std::string path = testing::TempDir() + "uavslam_no_such_dir/map.png";
  try {
    write_png(path, RgbImage(2, 2));
    FAIL() << "no FileError";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path));
    EXPECT_THAT(e.what(), HasSubstr("No such file or directory"));
  }
}

TEST_F(MapPictureTest, ReadingANonPngIsAFileErrorNamingThePath) {
  const std::string path = temp_path("not.png");
  std::ofstream(path) << "not a picture";
  try {
    read_png(path);
    FAIL() << "no FileError";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path));
  }
}

TEST_F(MapPictureTest, ViewFitsTheLongerSideAndKeepsTheMargin) {
  TopDownStyle style;
  style.max_side_px = 1000;
  style.margin_px = 10;
  const TopDownView view =
      fit_view(Eigen::AlignedBox2d(Eigen::Vector2d(-5, 0), Eigen::Vector2d(15, 10)), style);
  EXPECT_DOUBLE_EQ(view.pixels_per_metre, 50.0);
  EXPECT_EQ(view.width, 1020);
  EXPECT_EQ(view.height, 520);
  EXPECT_EQ(view.pixel_of(-5.0, 10.0), Eigen::Vector2i(10, 10));      // top-left of the bounds
  EXPECT_EQ(view.pixel_of(14.99, 0.01), Eigen::Vector2i(1009, 509));  // bottom-right
}

TEST_F(MapPictureTest, TopDownPictureShowsWallsFreeSpaceUnknownAndPath) {
  const octomap::OcTree tree = small_map();
  const TopDownMap map = render_top_down(&tree, path_along_y_equals_one());
  const std::string path = temp_path("topdown.png");
  write_png(path, map.image);
  const RgbImage picture = read_png(path);
  ASSERT_EQ(picture.width(), map.view.width);
  ASSERT_EQ(picture.height(), map.view.height);

  auto at = [&](double x, double y) {
    const Eigen::Vector2i p = map.view.pixel_of(x, y);
    return picture.at(p.x(), p.y());
  };
  EXPECT_EQ(at(2.05, 0.35), (Rgb{0, 0, 0})) << "the full-height wall is the darkest column";
  const Rgb box = at(0.55, 1.55);
  EXPECT_EQ(box[0], box[1]);
  EXPECT_GT(box[0], 0) << "one occupied cell is lighter than the wall";
  EXPECT_LT(box[0], 225) << "but darker than free space";
  EXPECT_EQ(at(1.25, 0.55), kFreeGrey);
  EXPECT_EQ(at(1.25, 1.25), kWhite) << "never observed";
  EXPECT_EQ(at(0.2, 1.0), kStartGreen);
  EXPECT_GT(map.scale_bar_m, 0.0);
}

TEST_F(MapPictureTest, PictureOfAPathWithoutAMap) {
  const TopDownMap map = render_top_down(nullptr, path_along_y_equals_one());
  EXPECT_GT(map.image.width(), 2 * map.view.margin_px);
  const Eigen::Vector2i start = map.view.pixel_of(0.2, 1.0);
  EXPECT_EQ(map.image.at(start.x(), start.y()), kStartGreen);
}

TEST_F(MapPictureTest, BtRoundTripKeepsTheOccupiedCells) {
  octomap::OcTree tree = small_map();
  const std::string path = temp_path("map.bt");
  write_bt(path, tree);
  const auto back = read_bt(path);
  EXPECT_DOUBLE_EQ(back->getResolution(), kResolution);
  EXPECT_EQ(occupied_cell_centres(*back).size(), 201u);
  ASSERT_NE(back->search(2.05, 0.45, 1.05), nullptr);
  EXPECT_TRUE(back->isNodeOccupied(back->search(2.05, 0.45, 1.05)));
}

TEST_F(MapPictureTest, OccupiedCentresDoNotDependOnPruning) {
  octomap::OcTree tree(kResolution);
  // A whole 2x2x2 block of the finest level: pruning replaces it by one leaf of 0.2 m.
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      for (int k = 0; k < 2; ++k) {
        for (int hits = 0; hits < 20; ++hits) {
          tree.updateNode(0.05 + 0.1 * i, 0.05 + 0.1 * j, 0.05 + 0.1 * k, true);
        }
      }
    }
  }
  tree.prune();
  ASSERT_EQ(tree.getNumLeafNodes(), 1u);
  const Points centres = occupied_cell_centres(tree);
  ASSERT_EQ(centres.size(), 8u);
  EXPECT_NEAR(centres.front().x(), 0.05, 1e-9);
  EXPECT_NEAR(centres.back().z(), 0.15, 1e-9);
}

TEST_F(MapPictureTest, BtErrorsNameThePath) {
  const std::string missing = testing::TempDir() + "uavslam_no_such_dir/map.bt";
  EXPECT_THROW(write_bt(missing, octomap::OcTree(kResolution)), FileError);
  const std::string garbage = temp_path("garbage.bt");
  std::ofstream(garbage) << "# not an octree\n";
  try {
    read_bt(garbage);
    FAIL() << "no FileError";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr(garbage));
  }
}

}  // namespace
}  // namespace uavslam::io
