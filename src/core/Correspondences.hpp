// The scan points m_i and their nearest map points d_i as weighted pairs (step 1 of the seed's
// ICP), with the map point's surface normal where the point-to-line metric uses one.
#pragma once

#include <vector>

#include "core/Types.hpp"

namespace uavslam {

struct Correspondences {
  Points scan;                         // m_i
  Points map;                          // d_i
  std::vector<std::size_t> map_index;  // d_i's index in the world map (which keyframe added it)
  std::vector<Vec3> weights;           // omega_i per axis (eq. 5.17)
  std::vector<Vec3> normals;  // empty (point-to-point), or per pair: the horizontal unit normal
                              // of the wall at d_i, zero where none is known
  std::vector<Vec3> scan_normals;  // empty, or per pair: the wall's normal at m_i from the scan
                                   // itself (what the scan can see, ScanInformation)
  bool empty() const { return scan.empty(); }
  bool has_normal(std::size_t i) const { return !normals.empty() && !normals[i].isZero(); }
};

// The part of pair i's residual r (m_i - d_i) the metric counts, per axis: point-to-point keeps
// it whole; point-to-line keeps, in the horizontal plane, its component along the wall's normal.
inline Vec3 counted_residual(const Correspondences& pairs, std::size_t i, const Vec3& r) {
  if (!pairs.has_normal(i)) return r;
  const Vec3& n = pairs.normals[i];
  const double along_normal = n.x() * r.x() + n.y() * r.y();
  return {along_normal * n.x(), along_normal * n.y(), r.z()};
}

}  // namespace uavslam
