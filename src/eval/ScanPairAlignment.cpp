#include "eval/ScanPairAlignment.hpp"

#include <cmath>

#include "core/Heading.hpp"
#include "core/ScanMatcher.hpp"
#include "core/ScanProjection.hpp"
#include "core/WorldMap.hpp"
#include "core/extensions/SurfaceNormals.hpp"

namespace uavslam::eval {
namespace {

// The first scan as the whole world map, in its own body frame (the pipeline's add to map).
WorldMap map_of(const Scan& scan, const SlamConfig& config) {
  WorldMap map(make_nearest_neighbour_index(config.nearest_neighbour),
               config.map.min_point_spacing);
  const ProjectedScan projected = project_scan(scan, Eigen::Quaterniond::Identity());
  const int k = config.map.subsample_every;
  std::vector<Vec3> normals;
  if (config.icp.metric == IcpMetric::PointToLine) {
    normals = keep_every_kth(estimate_normals(projected.points, projected.vertical), k);
  }
  map.add_points(keep_every_kth(projected.points, k), normals);
  return map;
}

}  // namespace

ScanPairAlignment align_scan_pair(const Scan& first, const Scan& second, const Relation& relation,
                                  const SlamConfig& config) {
  ScanPairAlignment alignment;
  alignment.motion = relation;
  const WorldMap map = map_of(first, config);
  // The second scan turned by the relation's yaw, as the pipeline turns a scan by its heading.
  const ProjectedScan projected = project_scan(second, yaw_rotation(relation.yaw));
  const int k = config.scan.subsample_every;
  const ScanPoints points =
      weigh_points(keep_every_kth(projected.points, k), keep_every_kth(projected.vertical, k),
                   config.icp.split_axes);
  if (map.empty() || points.points.empty()) return alignment;
  const MatchResult match = ScanMatcher(config.icp)
                                .match(map, points, Vec3(relation.x, relation.y, 0.0),
                                       config.icp.heading != HeadingMode::Source);
  alignment.outcome = match.outcome;
  alignment.iterations = match.iterations;
  if (match.outcome != ScanOutcome::Accepted) return alignment;
  alignment.motion.x = match.position.x();
  alignment.motion.y = match.position.y();
  alignment.motion.yaw = std::remainder(relation.yaw + match.yaw, 2.0 * M_PI);
  return alignment;
}

}  // namespace uavslam::eval
