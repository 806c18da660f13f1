#include <gtest/gtest.h>

#include "core/ScanProjection.hpp"
#include "core/extensions/FloorReturns.hpp"

namespace uavslam {
namespace {

// A scanner 1.5 m above the floor: three floor beams straight down, and level beams, one of which,
// pitched down, struck the floor 4 m ahead.
ProjectedScan tilted_scan() {
  ProjectedScan scan;
  const auto add = [&scan](const Vec3& p, bool vertical) {
    scan.points.push_back(p);
    scan.vertical.push_back(vertical);
  };
  add({0.10, 0.00, -1.50}, true);
  add({0.00, 0.10, -1.49}, true);
  add({-0.10, 0.00, -1.51}, true);
  add({4.10, 0.00, -1.48}, false);  // the floor strike
  add({0.00, 3.00, 0.00}, false);   // a wall beside, at the scanner's height
  add({2.00, 3.00, -1.30}, false);  // the same wall 0.2 m above the floor
  return scan;
}

TEST(FloorReturns, SetsAsideTheLevelBeamsThatStruckTheFloor) {
  ProjectedScan scan = tilted_scan();
  EXPECT_EQ(set_aside_floor_returns(scan, 0.1), 1u);
  ASSERT_EQ(scan.points.size(), 5u);
  ASSERT_EQ(scan.vertical.size(), 5u);
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    EXPECT_FALSE(!scan.vertical[i] && scan.points[i].z() < -1.4) << scan.points[i].transpose();
  }
  // The floor beams themselves are the floor's measurement, not strikes.
  EXPECT_TRUE(scan.vertical[0] && scan.vertical[1] && scan.vertical[2]);
  EXPECT_TRUE(scan.points[3].isApprox(Vec3(0.0, 3.0, 0.0)));
  EXPECT_TRUE(scan.points[4].isApprox(Vec3(2.0, 3.0, -1.3)));
}

TEST(FloorReturns, AWiderMarginAlsoTakesWhatIsNearTheFloor) {
  ProjectedScan scan = tilted_scan();
  EXPECT_EQ(set_aside_floor_returns(scan, 0.25), 2u);
  EXPECT_EQ(scan.points.size(), 4u);
}

TEST(FloorReturns, WithoutFloorBeamsNothingIsSetAside) {
  // A planar scanner (the 2D logs) measures no floor: its points all stay, however low.
  ProjectedScan scan = tilted_scan();
  scan.points.erase(scan.points.begin(), scan.points.begin() + 3);
  scan.vertical.erase(scan.vertical.begin(), scan.vertical.begin() + 3);
  EXPECT_EQ(set_aside_floor_returns(scan, 0.1), 0u);
  EXPECT_EQ(scan.points.size(), 3u);
}

TEST(FloorReturns, TheFloorsLevelIsTheMedianOfItsBeams) {
  // One floor beam on a box 0.6 m high does not raise the floor the strikes are judged by.
  ProjectedScan scan = tilted_scan();
  scan.points.push_back({0.2, 0.2, -0.90});
  scan.vertical.push_back(true);
  scan.points.push_back({0.3, 0.1, -1.50});
  scan.vertical.push_back(true);
  EXPECT_EQ(set_aside_floor_returns(scan, 0.1), 1u);
}

}  // namespace
}  // namespace uavslam
