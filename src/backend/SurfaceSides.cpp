#include "backend/SurfaceSides.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace uavslam::backend {
namespace {

// The reference points with a normal, by grid cell of `reach`: a point's neighbours within reach
// are in its cell and the eight around it.
class CellIndex {
 public:
  CellIndex(const SurfacePoints& reference, double reach) : reference_(reference), cell_(reach) {
    for (std::size_t i = 0; i < reference.points.size(); ++i) {
      if (reference.normals[i].isZero()) continue;
      cells_[key(cell_of(reference.points[i].x()), cell_of(reference.points[i].y()))].push_back(i);
    }
  }

  // The reference point within reach of p that a surface at p facing n matches: the nearest
  // whose normal faces the same way, else the nearest facing the other way (opposed); index -1
  // for none. A thin wall seen from both sides has both faces within reach: the scan's face
  // finds its own.
  std::pair<long, bool> partner(const Eigen::Vector2d& p, const Eigen::Vector2d& n) const {
    const long cx = cell_of(p.x()), cy = cell_of(p.y());
    long same = -1, other = -1;
    double same_distance = cell_ * cell_, other_distance = cell_ * cell_;
    for (long dx = -1; dx <= 1; ++dx) {
      for (long dy = -1; dy <= 1; ++dy) {
        const auto found = cells_.find(key(cx + dx, cy + dy));
        if (found == cells_.end()) continue;
        for (const std::size_t i : found->second) {
          const double d = (reference_.points[i] - p).squaredNorm();
          const bool facing = reference_.normals[i].dot(n) >= 0.0;
          long& best = facing ? same : other;
          double& best_distance = facing ? same_distance : other_distance;
          if (d <= best_distance) {
            best_distance = d;
            best = static_cast<long>(i);
          }
        }
      }
    }
    return same >= 0 ? std::pair{same, false} : std::pair{other, other >= 0};
  }

 private:
  long cell_of(double v) const { return std::lround(std::floor(v / cell_)); }
  // Unsigned: a negative cell shifted left is undefined.
  static std::uint64_t key(long x, long y) {
    return (static_cast<std::uint64_t>(x) << 32) ^ (static_cast<std::uint64_t>(y) & 0xffffffffULL);
  }

  const SurfacePoints& reference_;
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

}  // namespace

SideCount compare_sides(const SurfacePoints& reference, const SurfacePoints& scan,
                        const Eigen::Vector3d& pose, double reach) {
  const CellIndex index(reference, reach);
  const Eigen::Rotation2Dd turn(pose.z());
  SideCount count;
  std::vector<std::pair<Eigen::Vector2d, bool>> pairs;  // the reference's normal, opposed
  Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (scan.normals[i].isZero()) continue;
    const auto [j, opposed] =
        index.partner(turn * scan.points[i] + pose.head<2>(), turn * scan.normals[i]);
    if (j < 0) continue;
    const Eigen::Vector2d& n = reference.normals[static_cast<std::size_t>(j)];
    ++count.paired;
    count.opposed += opposed;
    pairs.emplace_back(n, opposed);
    information += n * n.transpose();
  }
  if (pairs.empty()) return count;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(information);
  const Eigen::Vector2d weakest = solver.eigenvectors().col(0);
  for (const auto& [n, opposed] : pairs) {
    if (std::abs(n.dot(weakest)) < std::sqrt(0.5)) continue;
    ++count.weak_paired;
    count.weak_opposed += opposed;
  }
  return count;
}

Eigen::Vector2d toward_scanner(const Eigen::Vector2d& point, const Eigen::Vector3d& normal) {
  const Eigen::Vector2d horizontal = normal.head<2>();
  // Under 45 degrees from the vertical, a normal says more of a floor than of a wall.
  if (horizontal.norm() < std::sqrt(0.5)) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d n = horizontal.normalized();
  return n.dot(-point) >= 0.0 ? n : Eigen::Vector2d(-n);
}

}  // namespace uavslam::backend
