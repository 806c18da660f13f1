// Order statistics of a sample, for the timing summaries (per-scan latency and the like).
#pragma once

#include <cstddef>
#include <vector>

namespace uavslam::eval {

// The p-th percentile (p in [0, 100]) with linear interpolation between the closest ranks, the
// definition of numpy.percentile's default: rank = p / 100 * (n - 1). Throws
// std::invalid_argument for an empty sample or p outside [0, 100].
double percentile(std::vector<double> values, double p);

struct SampleStats {
  std::size_t count = 0;
  double mean = 0.0;
  double p50 = 0.0;  // the median
  double p99 = 0.0;
  double max = 0.0;
};

// count, mean, median, 99th percentile and maximum; all zero for an empty sample.
SampleStats summarize(const std::vector<double>& values);

}  // namespace uavslam::eval
