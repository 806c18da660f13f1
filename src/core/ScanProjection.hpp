// Steps 1 and 2 of the pipeline: a scan's ranges become 3D points, rotated into the world frame
// by the orientation source (the seed trusts the IMU for rotation), then thinned to every k-th.
#pragma once

#include <cstddef>
#include <vector>

#include "core/Types.hpp"

namespace uavslam {

// A return is usable when it is finite and within the sensor's [min_range, max_range].
bool is_valid_range(float range, const ScanGeometry& geometry);

struct ProjectedScan {
  Points points;  // world-oriented, relative to the body origin (translation not applied)
  std::vector<bool> vertical;  // per point: the beam points more up/down than sideways (> 45 deg)
  std::size_t invalid = 0;     // ranges dropped as NaN, inf or out of range
};

// How the body moves while the scanner sweeps (beyond the seed): its rates, taken as constant over
// the sweep's few milliseconds.
struct SweepMotion {
  Vec3 angular_velocity = Vec3::Zero();  // rad/s, body frame (the gyro's)
  Vec3 velocity = Vec3::Zero();          // m/s, world frame
  bool moving() const { return !angular_velocity.isZero() || !velocity.isZero(); }
};

// Each beam in the world, from the body at the scan's stamp (at `position`: the origin places
// the points relative to it), as it fired. Without fire times or motion, every beam is placed
// from the stamp's pose.
class SweptSensor {
 public:
  // Keeps a reference to `geometry`, which must outlive it.
  SweptSensor(const ScanGeometry& geometry, const Eigen::Quaterniond& orientation,
              const SweepMotion& sweep, const Vec3& position = Vec3::Zero());
  // Beam i's return at `range`; and, if asked, the beam's direction.
  Vec3 point(std::size_t i, double range, Vec3* direction = nullptr) const;

 private:
  const ScanGeometry* geometry_;
  Eigen::Isometry3d at_stamp_;  // sensor frame -> the world at the stamp
  bool deskew_;
  Eigen::Matrix3d orientation_;
  Vec3 axis_ = Vec3::UnitZ();  // of the body's turn (body frame), at
  double rate_ = 0.0;          // rad/s
  Vec3 velocity_;
  Vec3 position_;
};

// p = R_imu * (mount * (r * direction)): each valid beam in the world orientation, relative to the
// body at the scan's stamp. With the geometry's fire times and a moving sweep, beam i is placed
// from where the body was when it fired, t_i after the stamp:
//   p_i = R_imu Exp(omega t_i) (mount * (r_i d_i)) + v t_i   (omega: body frame, v: world)
// (the motion compensation, or deskewing, of LiDAR odometry: KISS-ICP, FAST-LIO).
ProjectedScan project_scan(const Scan& scan, const Eigen::Quaterniond& orientation,
                           const SweepMotion& sweep = {});

// Removes from `scan` the points (and their flags) for which drop(i) holds, keeping the others in
// order; returns how many went.
template <typename Drop>
std::size_t remove_points(ProjectedScan& scan, Drop drop) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (drop(i)) continue;
    scan.points[kept] = scan.points[i];
    scan.vertical[kept] = scan.vertical[i];
    ++kept;
  }
  const std::size_t removed = scan.points.size() - kept;
  scan.points.resize(kept);
  scan.vertical.resize(kept);
  return removed;
}

// Keep every k-th point (seed: k = 5, 216 of 1080), starting with the first.
template <typename T>
std::vector<T> keep_every_kth(const std::vector<T>& items, int k) {
  if (k <= 1) return items;
  std::vector<T> kept;
  kept.reserve(items.size() / std::size_t(k) + 1);
  for (std::size_t i = 0; i < items.size(); i += std::size_t(k)) kept.push_back(items[i]);
  return kept;
}

}  // namespace uavslam
