// Beyond the seed's translation-only step (eq. 5.16): the correction that also turns the scan
// about the vertical axis through the body, so the heading is measured, not only trusted.
//
//   m -> R_z(yaw) (m - p) + p + t        (p: the body position the scan was taken from)
//
// Horizontal part: one Gauss-Newton step of the weighted least squares over (t_x, t_y, yaw),
// linearised at yaw = 0, with each pair's residual r_i and Jacobian J_i
//   point-to-point: r_i = (m_i - d_i)_xy,   J_i = [I_2 | (-q_y, q_x)^T],     q = m_i - p
//   point-to-line:  r_i = n_i . (m_i - d_i), J_i = [n_x, n_y, n_x (-q_y) + n_y q_x]
//   (J^T W J + Lambda) x = -(J^T W r + Lambda c)
// where Lambda holds the predicted start in place against the correction c made so far (a prior:
// cost Lambda |c + x|^2), as a fraction `prior_weight` of the information all pairs give the
// translation (and the yaw): it decides what the scan cannot see (a corridor's length) and keeps
// one bad scan from turning the heading far from the orientation source's prediction.
// With a robust scale, W also holds the Cauchy weight of each pair's residual (iteratively
// reweighted least squares across the ICP's iterations).
// Vertical part: the seed's per-axis mean, t_z = sum w_iz (d_iz - m_iz) / sum w_iz.
// The ICP iterates the step, so the linearisation's error vanishes as yaw -> 0.
#pragma once

#include "core/Correspondences.hpp"

namespace uavslam {

struct PlanarCorrection {
  double yaw = 0.0;  // rad, about the vertical through the body
  Vec3 translation = Vec3::Zero();
};

struct CorrectionOptions {
  bool estimate_yaw = true;   // false: yaw stays 0, only the translation is solved
  double prior_weight = 0.0;  // Lambda as a fraction of the pairs' information
  // m; each pair's weight is scaled by 1 / (1 + (|r_i| / robust_scale)^2) (the Cauchy kernel), so
  // a pair far off (a person walking by, a door that moved) pulls less than one on the wall.
  // 0: every pair in the gate counts fully.
  double robust_scale = 0.0;
};

// The correction that best moves the scan points onto the map, given the correction `so_far`
// already applied since the predicted start.
PlanarCorrection best_correction(const Correspondences& pairs, const Vec3& body,
                                 const CorrectionOptions& options,
                                 const PlanarCorrection& so_far = {});

// Turns the points about the body and moves them: the formula above.
void apply_correction(Points& points, const Vec3& body, const PlanarCorrection& correction);

}  // namespace uavslam
