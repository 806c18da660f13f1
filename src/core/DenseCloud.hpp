// The offline variant's product (seed 5.4.3.3): every valid point of every posed scan in the world
// frame, for inspection and for export to point-cloud registration software. A voxel grid keeps
// its size bounded by the space mapped rather than by the length of the log: each voxel holds the
// centroid of the points that fell in it (their mean intensity, the time of the first).
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/Types.hpp"

namespace uavslam {

struct DensePoint {
  Vec3 position = Vec3::Zero();
  float intensity = 0.0f;  // mean of the voxel's returns; 0 when the sensor gives none
  double time = 0.0;       // s; the stamp of the first scan that hit the voxel
};

class DenseCloud {
 public:
  // voxel: the edge of a grid cell in metres; <= 0 keeps every point (no filter). Throws
  // std::invalid_argument on a non-finite voxel.
  explicit DenseCloud(double voxel);

  // Every valid return of the scan, placed by the pose the matcher gave it:
  // p = t + R (mount (r d)), the same projection as the matcher's (ScanProjection.hpp).
  void add_scan(const Scan& scan, const Pose& pose);
  void add_point(const Vec3& position, float intensity, double time);

  std::vector<DensePoint> points() const;
  std::size_t size() const;
  std::uint64_t points_added() const { return points_added_; }
  double voxel() const { return voxel_; }

 private:
  struct Voxel {
    Vec3 sum = Vec3::Zero();
    double intensity_sum = 0.0;
    double first_time = 0.0;
    std::uint32_t count = 0;
  };
  struct KeyHash {
    std::size_t operator()(const Eigen::Vector3i& key) const;
  };
  struct KeyEqual {
    bool operator()(const Eigen::Vector3i& a, const Eigen::Vector3i& b) const { return a == b; }
  };

  double voxel_;
  std::unordered_map<Eigen::Vector3i, Voxel, KeyHash, KeyEqual> voxels_;
  std::vector<DensePoint> unfiltered_;
  std::uint64_t points_added_ = 0;
};

}  // namespace uavslam
