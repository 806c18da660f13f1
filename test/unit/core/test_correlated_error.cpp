// An error as the sum of the independent noises it came from: covariances and correlations exact,
// what is pruned taken as shared.
#include <gtest/gtest.h>

#include "core/extensions/CorrelatedError.hpp"

namespace uavslam {
namespace {

Eigen::Matrix4d variances(double x, double y, double z, double yaw) {
  return Eigen::Vector4d(x, y, z, yaw).asDiagonal();
}

TEST(CorrelatedError, ItsCovarianceIsTheSumOfItsNoisesCovariances) {
  CorrelatedError error;
  EXPECT_TRUE(error.covariance().isZero());
  Eigen::Matrix4d correlated = variances(4.0, 1.0, 0.0, 0.01);
  correlated(0, 3) = correlated(3, 0) = 0.1;
  error.add_noise(3, correlated);
  error.add_noise(1, variances(1.0, 1.0, 1.0, 0.0));
  EXPECT_EQ(error.sources(), 2u);
  EXPECT_TRUE(error.covariance().isApprox(correlated + variances(1.0, 1.0, 1.0, 0.0)));
}

// e = e_1 + e_2 with e_2 = 2 e_1 + n: the shared noise adds by its coefficients (1 + 2)^2, the
// other's by its variance.
TEST(CorrelatedError, ASharedNoiseAddsByItsCoefficients) {
  CorrelatedError first;
  first.add_noise(0, variances(1.0, 0.0, 0.0, 0.0));
  CorrelatedError second;
  second.add(2.0 * Eigen::Matrix4d::Identity(), first);
  second.add_noise(1, variances(3.0, 0.0, 0.0, 0.0));
  CorrelatedError sum = first;
  sum.add(Eigen::Matrix4d::Identity(), second);
  EXPECT_NEAR(sum.covariance()(0, 0), 9.0 + 3.0, 1e-12);
  // Taken apart, e_2 - 2 e_1 is n alone.
  CorrelatedError difference = second;
  difference.add(-2.0 * Eigen::Matrix4d::Identity(), first);
  EXPECT_NEAR(difference.covariance()(0, 0), 3.0, 1e-12);
}

TEST(CorrelatedError, AForgottenAxisHoldsNothing) {
  CorrelatedError error;
  Eigen::Matrix4d covariance = variances(1.0, 2.0, 3.0, 4.0);
  covariance(1, 2) = covariance(2, 1) = 1.0;
  error.add_noise(0, covariance);
  error.forget(2);
  const Eigen::Matrix4d left = error.covariance();
  EXPECT_NEAR(left.row(2).norm() + left.col(2).norm(), 0.0, 1e-12);
  EXPECT_NEAR(left(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(left(3, 3), 4.0, 1e-12);
}

// Pruned to two, the smallest noises join the common source: the covariance is the same, and two
// errors that each pruned an independent noise now share it (the shared-error assumption).
TEST(CorrelatedError, PrunedNoisesKeepTheCovarianceAndAreTakenAsShared) {
  CorrelatedError error;
  for (std::size_t j = 0; j < 5; ++j) error.add_noise(j, variances(1.0 + j, 1.0, 0.0, 0.0));
  const Eigen::Matrix4d before = error.covariance();
  error.prune(2);
  EXPECT_EQ(error.sources(), 3u);
  EXPECT_TRUE(error.covariance().isApprox(before));

  CorrelatedError a;
  a.add_noise(0, variances(1.0, 0.0, 0.0, 0.0));
  a.add_noise(1, variances(4.0, 0.0, 0.0, 0.0));
  CorrelatedError b;
  b.add_noise(2, variances(1.0, 0.0, 0.0, 0.0));
  b.add_noise(3, variances(4.0, 0.0, 0.0, 0.0));
  CorrelatedError sum = a;
  sum.add(Eigen::Matrix4d::Identity(), b);
  EXPECT_NEAR(sum.covariance()(0, 0), 10.0, 1e-12);
  a.prune(1);
  b.prune(1);
  sum = a;
  sum.add(Eigen::Matrix4d::Identity(), b);
  EXPECT_NEAR(sum.covariance()(0, 0), 4.0 + 4.0 + 4.0, 1e-12);  // (1 + 1)^2 for the shared
  a.prune(1);                                                   // already within: unchanged
  EXPECT_EQ(a.sources(), 2u);
}

}  // namespace
}  // namespace uavslam
