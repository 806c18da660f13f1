#include "core/extensions/Relocalisation.hpp"

#include <algorithm>
#include <cmath>

namespace uavslam {
namespace {

// Alignments pairing within this share of the best pair count are compared by their error.
constexpr double kPairsTolerance = 0.95;

bool better(const MatchResult& candidate, const MatchResult& best) {
  const double most = std::max(candidate.correspondences, best.correspondences);
  const bool candidate_close = candidate.correspondences >= kPairsTolerance * most;
  const bool best_close = best.correspondences >= kPairsTolerance * most;
  if (candidate_close != best_close) return candidate_close;
  return candidate.error_after < best.error_after;
}

}  // namespace

double search_radius(const SlamConfig::Recovery& recovery, double gap) {
  return std::min(recovery.max_speed * gap, recovery.max_radius);
}

std::vector<Vec3> search_starts(const Vec3& centre, double radius, double step) {
  std::vector<Vec3> starts;
  const int cells = static_cast<int>(std::floor(radius / step));
  for (int i = -cells; i <= cells; ++i) {
    for (int j = -cells; j <= cells; ++j) {
      const Vec3 offset(i * step, j * step, 0.0);
      if (offset.norm() <= radius + 1e-9) starts.push_back(centre + offset);
    }
  }
  std::sort(starts.begin(), starts.end(), [&](const Vec3& a, const Vec3& b) {
    return (a - centre).squaredNorm() < (b - centre).squaredNorm();
  });
  return starts;
}

MatchResult relocalise(const ScanMatcher& matcher, const WorldMap& map, const ScanPoints& scan,
                       const std::vector<Vec3>& starts, bool estimate_yaw) {
  MatchResult best;
  bool found = false;
  for (const Vec3& start : starts) {
    MatchResult candidate = matcher.match(map, scan, start, estimate_yaw);
    if (candidate.outcome != ScanOutcome::Accepted) {
      if (!found && &start == &starts.front()) best = std::move(candidate);
      continue;
    }
    if (!found || better(candidate, best)) best = std::move(candidate);
    found = true;
  }
  return best;
}

}  // namespace uavslam
