// Beyond the seed: finding the vehicle again after a gap in the scans (a link outage with the
// matcher on the ground, a sensor dropout). The seed's ICP starts from the last position and
// corrects at most max_translation; after a gap of seconds the vehicle may be metres away, where
// one start converges to the wrong wall or not at all. So the ICP is started from every point of
// a horizontal grid over the disc the vehicle can have covered (speed x gap, capped), and the
// accepted alignment that pairs the most scan points wins (the smallest error among those within
// a few pairs of the most): a wrong alignment leaves part of the scan without partners.
#pragma once

#include <vector>

#include "core/ScanMatcher.hpp"
#include "core/SlamConfig.hpp"

namespace uavslam {

// The search radius after `gap` seconds without a scan: recovery.max_speed x gap, at most
// recovery.max_radius.
double search_radius(const SlamConfig::Recovery& recovery, double gap);

// The starts: `centre` and the points of a square grid of `step` within `radius` of it in x-y,
// nearest first.
std::vector<Vec3> search_starts(const Vec3& centre, double radius, double step);

// The best accepted match over the starts; when none was accepted, the first start's result.
MatchResult relocalise(const ScanMatcher& matcher, const WorldMap& map, const ScanPoints& scan,
                       const std::vector<Vec3>& starts, bool estimate_yaw);

}  // namespace uavslam
