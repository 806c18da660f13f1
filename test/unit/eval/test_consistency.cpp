// NEES: the error weighed by the reported covariance, over the axes the covariance states.
#include <gtest/gtest.h>

#include "eval/Consistency.hpp"

namespace uavslam::eval {
namespace {

TEST(Consistency, NeesWeighsTheErrorByTheCovariance) {
  const Eigen::Matrix3d covariance = Eigen::Vector3d(0.04, 0.01, 0.0).asDiagonal();
  const auto n = nees(Vec3(0.2, 0.1, 5.0), covariance);  // z: not estimated, not counted
  ASSERT_TRUE(n);
  EXPECT_EQ(n->dimension, 2);
  EXPECT_NEAR(n->value, 1.0 + 1.0, 1e-12);
  EXPECT_FALSE(nees(Vec3(1, 1, 1), Eigen::Matrix3d::Zero()));
}

TEST(Consistency, TheMeanOfAConsistentRunIsTheDimension) {
  const NeesSummary s = summarize({{1.0, 3}, {5.0, 3}, {2.0, 2}, {4.0, 2}});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_DOUBLE_EQ(s.mean_dimension, 2.5);
}

}  // namespace
}  // namespace uavslam::eval
