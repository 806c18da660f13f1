// The map's own uncertainty: a match inherits the covariance of the keyframes whose points it
// paired with.
#include <gtest/gtest.h>

#include "core/extensions/MapUncertainty.hpp"

namespace uavslam {
namespace {

Eigen::Matrix3d isotropic(double variance) {
  return variance * Eigen::Matrix3d::Identity();
}

TEST(MapUncertainty, AMatchInheritsTheMeanOfItsPairsKeyframes) {
  MapUncertainty map;
  map.add_keyframe(0, isotropic(0.0));    // points 0..99: the take-off, the map's anchor
  map.add_keyframe(100, isotropic(4.0));  // points 100..149
  map.add_keyframe(150, isotropic(1.0));  // points 150..
  EXPECT_TRUE(map.of_points({}).isZero());
  EXPECT_TRUE(map.of_points({0, 5, 99}).isZero());
  EXPECT_TRUE(map.of_points({100, 149}).isApprox(isotropic(4.0)));
  EXPECT_TRUE(map.of_points({150, 1000}).isApprox(isotropic(1.0)));
  // Three pairs on the anchor, one on each of the others: (0 + 0 + 0 + 4 + 1) / 5.
  EXPECT_TRUE(map.of_points({1, 2, 3, 120, 160}).isApprox(isotropic(1.0)));
}

TEST(MapUncertainty, AKeyframeThatAddedNothingOwnsNoPoint) {
  MapUncertainty map;
  map.add_keyframe(0, isotropic(1.0));
  map.add_keyframe(10, isotropic(9.0));  // every point within the spacing of older ones
  map.add_keyframe(10, isotropic(2.0));
  EXPECT_TRUE(map.of_points({10, 11}).isApprox(isotropic(2.0)));
  EXPECT_TRUE(map.of_points({9}).isApprox(isotropic(1.0)));
}

}  // namespace
}  // namespace uavslam
