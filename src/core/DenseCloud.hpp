// The offline variant's product (seed 5.4.3.3): every valid point of every posed scan in the world
// frame, for inspection and for export to point-cloud registration software. A voxel grid keeps
// its size bounded by the space mapped rather than by the length of the log: each voxel holds the
// centroid of the points that fell in it (their mean intensity, the time of the first).
#pragma once

#include <cstddef>
#include <cstdint>
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

  // In the order the voxels were first hit: scan order, as a reader of the cloud expects.
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
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

  Voxel& voxel_at(std::uint64_t key);
  void grow();

  double voxel_;
  // An open-addressing hash table (linear probing) from the packed voxel key to the voxel: one
  // allocation for millions of voxels where a node-based map makes one each.
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> slots_;  // index into voxels_, per key
  std::vector<Voxel> voxels_;
  std::vector<DensePoint> unfiltered_;
  std::uint64_t points_added_ = 0;
};

}  // namespace uavslam
