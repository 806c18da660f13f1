// The offline variant's product (seed 5.4.3.3): every valid point of every posed scan in the world
// frame, for inspection and for export to point-cloud registration software. A voxel grid keeps
// its size bounded by the space mapped rather than by the length of the log: each voxel holds the
// centroid of the points that fell in it (their mean intensity, the time of the first).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/ScanProjection.hpp"
#include "core/Types.hpp"
#include "maps/HugePageAllocator.hpp"

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
  // p = t + R (mount (r d)), the same projection as the matcher's (ScanProjection.hpp), each beam
  // from where the body was when it fired given the sweep's motion.
  void add_scan(const Scan& scan, const Pose& pose, const SweepMotion& sweep = {});
  void add_point(const Vec3& position, float intensity, double time);

  // In the order the voxels were first hit: scan order, as a reader of the cloud expects.
  std::vector<DensePoint> points() const;
  std::size_t size() const;
  std::uint64_t points_added() const { return points_added_; }
  double voxel() const { return voxel_; }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  // One voxel, in the hash table itself (open addressing, linear probing): a point costs one
  // memory access, and millions of voxels one allocation. The sums are offsets from the voxel's
  // corner, small enough for float.
  struct Voxel {
    std::uint64_t key = kEmpty;
    float sum[3] = {0.0f, 0.0f, 0.0f};
    float intensity_sum = 0.0f;
    double first_time = 0.0;
    std::uint32_t count = 0;
    std::uint32_t order = 0;  // how many voxels were hit before this one
  };
  // A point on its way into the table: its voxel's key and its offset from the voxel's corner.
  struct Placed {
    std::uint64_t key;
    Vec3 offset;
    float intensity;
  };

  bool place(const Vec3& position, float intensity, Placed& placed) const;
  void accumulate(const Placed& placed, double time);
  void make_room_for(std::size_t more_voxels);
  Vec3 corner_of(std::uint64_t key) const;

  double voxel_;
  std::vector<Voxel, HugePageAllocator<Voxel>> table_;
  std::size_t voxel_count_ = 0;
  std::vector<Placed> placed_;  // one scan's, reused
  std::vector<DensePoint> unfiltered_;
  std::uint64_t points_added_ = 0;
};

}  // namespace uavslam
