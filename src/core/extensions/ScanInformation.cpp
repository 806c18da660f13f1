#include "core/extensions/ScanInformation.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace uavslam {
namespace {

// The pairs' mean squared residual along their normals, at least min_sigma^2.
double residual_variance(const Correspondences& pairs, double min_sigma) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < pairs.scan.size(); ++i) {
    const Vec3& n = pairs.scan_normals[i];
    if (n.isZero() || pairs.weights[i].x() <= 0.0) continue;
    const double along = n.head<2>().dot((pairs.scan[i] - pairs.map[i]).head<2>());
    sum += along * along;
    ++count;
  }
  const double variance = count > 0 ? sum / double(count) : 0.0;
  return std::max(variance, min_sigma * min_sigma);
}

// J above: the residual's change per unit of t_x, t_y and yaw about the body.
Eigen::Vector3d horizontal_jacobian(const Vec3& normal, const Vec3& from_body) {
  return {normal.x(), normal.y(), -normal.x() * from_body.y() + normal.y() * from_body.x()};
}

}  // namespace

ScanInformation scan_information(const Correspondences& pairs, const Vec3& body, bool with_yaw,
                                 double min_sigma) {
  ScanInformation info;
  if (pairs.scan_normals.size() != pairs.scan.size()) return info;
  const double variance = residual_variance(pairs, min_sigma);
  info.sigma = std::sqrt(variance);
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();  // over (t_x, t_y, yaw)
  double vertical = 0.0;
  double levers = 0.0;  // sum_i w_i |q_i|^2, the most the pairs could say of the yaw
  for (std::size_t i = 0; i < pairs.scan.size(); ++i) {
    const Vec3& w = pairs.weights[i];
    const Vec3& n = pairs.scan_normals[i];
    if (w.z() > 0.0) {
      vertical += w.z();
      ++info.vertical_pairs;
    }
    if (w.x() <= 0.0 || n.isZero()) continue;
    const Eigen::Vector3d J = horizontal_jacobian(n, pairs.scan[i] - body);
    H.noalias() += w.x() * J * J.transpose();
    levers += w.x() * (pairs.scan[i] - body).head<2>().squaredNorm();
    ++info.horizontal_pairs;
  }
  Eigen::Matrix2d translation = H.topLeftCorner<2, 2>();
  if (with_yaw && H(2, 2) > 0.0) {
    translation -= H.topRightCorner<2, 1>() * H.bottomLeftCorner<1, 2>() / H(2, 2);
    // The yaw's information with the translation estimated beside it (the other Schur
    // complement): H_yy - H_yt H_tt^-1 H_ty.
    const Eigen::Matrix2d Htt = H.topLeftCorner<2, 2>();
    if (std::abs(Htt.determinant()) > 0.0) {
      const double yaw_information =
          H(2, 2) - (H.bottomLeftCorner<1, 2>() * Htt.inverse() * H.topRightCorner<2, 1>())(0, 0);
      if (yaw_information > 0.0) info.yaw_variance = variance / yaw_information;
      if (levers > 0.0) info.yaw_fraction = std::max(yaw_information, 0.0) / levers;
    }
  }
  info.translation.topLeftCorner<2, 2>() = translation / variance;
  info.translation(2, 2) = vertical / variance;
  return info;
}

Eigen::Matrix4d pair_joint_information(const Correspondences& pairs, std::size_t i,
                                       const Vec3& body) {
  Eigen::Matrix4d information = Eigen::Matrix4d::Zero();
  const Vec3& w = pairs.weights[i];
  information(2, 2) = std::max(w.z(), 0.0);
  if (i >= pairs.scan_normals.size() || w.x() <= 0.0) return information;
  const Eigen::Vector3d J = horizontal_jacobian(pairs.scan_normals[i], pairs.scan[i] - body);
  const Eigen::Vector4d J4(J.x(), J.y(), 0.0, J.z());
  information.noalias() += w.x() * J4 * J4.transpose();
  return information;
}

Observability observability(const ScanInformation& information, double threshold,
                            bool measures_height) {
  Observability result;
  result.yaw_variance = information.yaw_variance;
  const double variance = information.sigma * information.sigma;
  const double pairs = double(information.horizontal_pairs);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(
      information.translation.topLeftCorner<2, 2>());
  result.observed.setZero();
  for (int k = 0; k < 2; ++k) {
    const double value = solver.eigenvalues()[k];  // ascending
    const Eigen::Vector2d e = solver.eigenvectors().col(k);
    const double fraction = pairs > 0.0 ? value * variance / pairs : 0.0;
    if (k == 0) {
      result.weakest = Vec3(e.x(), e.y(), 0.0);
      result.weakest_fraction = fraction;
    }
    if (fraction < threshold) {
      ++result.degenerate;
      continue;
    }
    result.observed.topLeftCorner<2, 2>() += e * e.transpose();
    result.covariance.topLeftCorner<2, 2>() += e * e.transpose() / value;
  }
  const double vertical = information.translation(2, 2);
  if (vertical > 0.0 && information.vertical_pairs > 0) {
    result.observed(2, 2) = 1.0;
    result.covariance(2, 2) = 1.0 / vertical;
  } else if (measures_height) {
    ++result.degenerate;
  }
  return result;
}

Eigen::Matrix<double, 3, Eigen::Dynamic> observed_basis(const Eigen::Matrix3d& observed) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> projection(observed);
  Eigen::Matrix<double, 3, Eigen::Dynamic> basis(3, 0);
  for (int i = 0; i < 3; ++i) {
    if (projection.eigenvalues()(i) < 0.5) continue;
    basis.conservativeResize(Eigen::NoChange, basis.cols() + 1);
    basis.col(basis.cols() - 1) = projection.eigenvectors().col(i);
  }
  return basis;
}

}  // namespace uavslam
