// Does the match agree with the motion prior (beyond the seed, icp.prior_gate)? In the directions
// the scan fixed (Observability::observed, P), the match's correction of the predicted position is
// an innovation whose covariance is the match's plus the prediction's (the Kalman filter's test
// of a measurement against its prediction; FAST-LIO and LIO-SAM gate their updates the same way):
//   nu = P (p_match - p_predicted),   S = Sigma_scan + Sigma_predicted
//   d  = sqrt(nu_E^T S_E^-1 nu_E),    nu_E = E^T nu, S_E = E^T S E
// (E: an orthonormal basis of the observed directions, where S is invertible). A match that only
// looks good, a wall taken for its neighbour or a symmetric room's twin, is many sigmas away.
#pragma once

#include "core/Types.hpp"
#include "core/extensions/ScanInformation.hpp"

namespace uavslam {

struct PriorDistance {
  double sigmas = 0.0;  // d; 0 when the scan fixed no direction
  int directions = 0;   // the observed directions it is measured over (d^2's degrees of freedom)
};

// The Mahalanobis distance of the match's correction from the prediction, given the projection
// onto the observed directions (P) and the innovation's covariance (S).
PriorDistance distance_from_prior(const Vec3& correction, const Eigen::Matrix3d& observed,
                                  const Eigen::Matrix3d& innovation_covariance);

}  // namespace uavslam
