#include <stdexcept>

#include <gtest/gtest.h>

#include "eval/Percentile.hpp"

namespace uavslam::eval {
namespace {

TEST(Percentile, InterpolatesLinearlyBetweenRanks) {
  const std::vector<double> values = {4.0, 1.0, 3.0, 2.0};  // unsorted on purpose
  EXPECT_DOUBLE_EQ(percentile(values, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(percentile(values, 25.0), 1.75);  // rank 0.75 (numpy.percentile)
  EXPECT_DOUBLE_EQ(percentile(values, 50.0), 2.5);
  EXPECT_DOUBLE_EQ(percentile(values, 100.0), 4.0);
}

TEST(Percentile, OfOneValueIsThatValue) {
  EXPECT_DOUBLE_EQ(percentile({7.0}, 0.0), 7.0);
  EXPECT_DOUBLE_EQ(percentile({7.0}, 99.0), 7.0);
}

TEST(Percentile, RejectsEmptySamplesAndPOutsideTheRange) {
  EXPECT_THROW(percentile({}, 50.0), std::invalid_argument);
  EXPECT_THROW(percentile({1.0, 2.0}, -1.0), std::invalid_argument);
  EXPECT_THROW(percentile({1.0, 2.0}, 100.5), std::invalid_argument);
}

TEST(SampleStats, SummarizesOneToOneHundred) {
  std::vector<double> values;
  for (int i = 100; i >= 1; --i) values.push_back(i);
  const SampleStats stats = summarize(values);
  EXPECT_EQ(stats.count, 100u);
  EXPECT_DOUBLE_EQ(stats.mean, 50.5);
  EXPECT_DOUBLE_EQ(stats.p50, 50.5);
  EXPECT_DOUBLE_EQ(stats.p99, 99.01);  // rank 0.99 * 99 = 98.01
  EXPECT_DOUBLE_EQ(stats.max, 100.0);
}

TEST(SampleStats, OfNothingIsAllZero) {
  const SampleStats stats = summarize({});
  EXPECT_EQ(stats.count, 0u);
  EXPECT_EQ(stats.mean, 0.0);
  EXPECT_EQ(stats.max, 0.0);
}

}  // namespace
}  // namespace uavslam::eval
