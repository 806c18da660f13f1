// A rectangular room seen by a planar scanner, computed in closed form: scans for core tests
// that must not depend on the simulator.
#pragma once

#include <cmath>
#include <limits>
#include <memory>

#include "core/Types.hpp"

namespace uavslam::test {

// Inside an axis-aligned box, the distance along a ray to the box's boundary.
inline double distance_to_box_wall(const Vec3& origin, const Vec3& dir, const Vec3& lo,
                                   const Vec3& hi) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (std::abs(dir[k]) < 1e-12) continue;
    const double t = ((dir[k] > 0 ? hi[k] : lo[k]) - origin[k]) / dir[k];
    if (t > 0 && t < best) best = t;
  }
  return best;
}

// An orientation sample of a level body heading along x (the identity), at `stamp`.
inline ImuSample level_imu(double stamp) {
  ImuSample s;
  s.stamp = stamp;
  return s;
}

struct SyntheticRoom {
  Vec3 lo{0, 0, 0};
  Vec3 hi{12, 7, 3};
  // A pillar breaks the symmetry of the rectangle.
  Vec3 pillar_lo{8, 2, 0};
  Vec3 pillar_hi{8.6, 2.6, 3};
  std::shared_ptr<ScanGeometry> geometry;

  SyntheticRoom() {
    geometry = std::make_shared<ScanGeometry>(
        ScanGeometry::planar(-135.0 * M_PI / 180.0, 270.0 / 1079.0 * M_PI / 180.0, 1080));
  }

  double distance_to_pillar(const Vec3& o, const Vec3& d) const {
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (std::abs(d[k]) < 1e-12) {
        if (o[k] < pillar_lo[k] || o[k] > pillar_hi[k])
          return std::numeric_limits<double>::infinity();
        continue;
      }
      double a = (pillar_lo[k] - o[k]) / d[k], b = (pillar_hi[k] - o[k]) / d[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    return t0 <= t1 && t0 > 0 ? t0 : std::numeric_limits<double>::infinity();
  }

  Scan scan_at(const Pose& body, double stamp) const {
    Scan scan;
    scan.stamp = stamp;
    scan.geometry = geometry;
    const Eigen::Isometry3d sensor = body.isometry() * geometry->mount;
    for (const Vec3& d : geometry->directions) {
      const Vec3 dir = sensor.linear() * d;
      const Vec3 o = sensor.translation();
      const double r = std::min(distance_to_box_wall(o, dir, lo, hi), distance_to_pillar(o, dir));
      scan.ranges.push_back(float(r));
    }
    return scan;
  }
};

}  // namespace uavslam::test
