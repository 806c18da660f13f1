#include "core/extensions/SurfaceNormals.hpp"

#include <Eigen/Eigenvalues>

namespace uavslam {
namespace {

// The 2D scatter of the neighbours within the gap around point i: its smallest principal axis is
// the normal of the line through them.
Vec3 normal_at(const Points& points, const std::vector<bool>& vertical, std::size_t i,
               const SurfaceNormalOptions& options) {
  const std::size_t first = i >= std::size_t(options.half_window) ? i - options.half_window : 0;
  const std::size_t last = std::min(points.size() - 1, i + std::size_t(options.half_window));
  const double max_squared = options.max_neighbour_gap * options.max_neighbour_gap;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d outer = Eigen::Matrix2d::Zero();
  int count = 0;
  for (std::size_t j = first; j <= last; ++j) {
    if (vertical[j] || (points[j] - points[i]).head<2>().squaredNorm() > max_squared) continue;
    const Eigen::Vector2d p = points[j].head<2>();
    sum += p;
    outer += p * p.transpose();
    ++count;
  }
  if (count < 3) return Vec3::Zero();
  const Eigen::Vector2d mean = sum / count;
  const Eigen::Matrix2d scatter = outer / count - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(scatter);
  const Eigen::Vector2d values = solver.eigenvalues();  // ascending
  if (values[1] <= 0.0 || values[0] > options.max_flatness * values[1]) return Vec3::Zero();
  Eigen::Vector2d normal = solver.eigenvectors().col(0);
  // Facing the scanner (the points are relative to it): a wall's two faces are told apart.
  if (normal.dot(points[i].head<2>()) > 0.0) normal = -normal;
  return {normal.x(), normal.y(), 0.0};
}

}  // namespace

std::vector<Vec3> estimate_normals(const Points& ordered_points, const std::vector<bool>& vertical,
                                   const SurfaceNormalOptions& options) {
  std::vector<Vec3> normals(ordered_points.size(), Vec3::Zero());
  for (std::size_t i = 0; i < ordered_points.size(); ++i) {
    if (!vertical[i]) normals[i] = normal_at(ordered_points, vertical, i, options);
  }
  return normals;
}

}  // namespace uavslam
