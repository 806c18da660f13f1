// What the scan can see (beyond the seed): the information the matched pairs give each direction of
// the body's translation, from the point-to-line normal equations at convergence (the Hessian of
// Censi 2007 and of Hector SLAM; the degeneracy test of Zhang, Kaess & Singh 2016):
//   horizontal, over (t_x, t_y, yaw):  H = sum_i w_i J_i J_i^T / sigma^2,
//                                      J_i = [n_x, n_y, n_x (-q_y) + n_y q_x]
//     (n_i: the wall's normal at the scan point m_i, q_i = m_i - p, p the body)
//   vertical:                          H_zz = sum_i w_iz / sigma^2   (floor and ceiling beams)
// Point-to-point pairs hold the same information: a point on a wall fixes only its distance to the
// wall, whatever the metric. With the yaw estimated too, the translation keeps the Schur complement
//   H_tt - H_ty H_yy^-1 H_yt   (what is left once the yaw is free to absorb the pairs).
// sigma^2 is the pairs' mean squared residual along their normals, at least min_sigma^2.
//
// A direction e is degenerate when its information, as a fraction of what the pairs would give
// were every normal along e (e^T H e / (N / sigma^2): the mean of (n_i . e)^2), is under
// `threshold`: the walls leave it free (a corridor's axis, a single wall's length).
#pragma once

#include <cstddef>

#include "core/Correspondences.hpp"

namespace uavslam {

struct ScanInformation {
  Eigen::Matrix3d translation = Eigen::Matrix3d::Zero();  // 1/m^2, over (x, y, z)
  std::size_t horizontal_pairs = 0;                       // pairs with a wall normal
  std::size_t vertical_pairs = 0;                         // pairs on the floor or ceiling
  double sigma = 0.0;                                     // m
  // rad^2: the yaw's variance with the translation estimated beside it (with_yaw; else 0)
  double yaw_variance = 0.0;
  // The yaw's information with the translation estimated beside it, as a fraction of what the
  // pairs would give were each normal square to its lever (sum_i w_i |q_i|^2): near 0 where a
  // turn and a shift together leave the scan unchanged (a round room); 1 without the yaw.
  double yaw_fraction = 1.0;
};

// Uses pairs.scan_normals (the scan's own normals, ScanPoints::normals); none: no information.
ScanInformation scan_information(const Correspondences& pairs, const Vec3& body, bool with_yaw,
                                 double min_sigma);

// Pair i's information over (x, y, z, yaw) for a body at `body`, in units of the residual
// variance: w_x J J^T horizontally (J above, the yaw's column the turn about the body; none
// without the wall's normal from the scan), w_z on z. Its top-left 3 x 3 is the information on
// the translation alone, w_x n n^T and w_z, whatever the body.
Eigen::Matrix4d pair_joint_information(const Correspondences& pairs, std::size_t i,
                                       const Vec3& body);

struct Observability {
  // Projection onto the directions the scan fixes: a position measured by the scan keeps
  // P (measured - predicted) of its correction; the rest stays as predicted.
  Eigen::Matrix3d observed = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // m^2: H^-1 on the observed directions
  int degenerate = 0;                                    // directions the scan leaves free
  Vec3 weakest = Vec3::UnitX();   // the horizontal direction the scan sees least
  double weakest_fraction = 0.0;  // its information fraction (see above)
  double yaw_variance = 0.0;      // rad^2, ScanInformation's
};

// An orthonormal basis (columns) of the directions a projection like Observability::observed keeps
// (its eigenvalues are 0 or 1); no columns when the scan fixed none.
Eigen::Matrix<double, 3, Eigen::Dynamic> observed_basis(const Eigen::Matrix3d& observed);

// z counts only when the scan has floor or ceiling beams (measures_height); a planar scanner
// without them never estimates height, and its z is not called degenerate.
Observability observability(const ScanInformation& information, double threshold,
                            bool measures_height);

}  // namespace uavslam
