#include "core/extensions/FloorBelow.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace uavslam {
namespace {

constexpr std::size_t kMinFloorPoints = 3;
constexpr double kMadToSigma = 1.4826;  // a normal distribution's sigma over its MAD

double median_of(std::vector<double>& values) {
  const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

std::optional<FloorSighting> floor_below(const ProjectedScan& scan) {
  std::vector<double> heights;  // of the floor's points, relative to the body
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (scan.vertical[i] && scan.points[i].z() < 0.0) heights.push_back(scan.points[i].z());
  }
  if (heights.size() < kMinFloorPoints) return std::nullopt;
  FloorSighting floor;
  floor.beams = heights.size();
  floor.below = -median_of(heights);
  for (double& h : heights) h = std::abs(h + floor.below);
  const double sigma = kMadToSigma * median_of(heights);
  floor.variance = M_PI / 2.0 * sigma * sigma / double(floor.beams);
  return floor;
}

}  // namespace uavslam
