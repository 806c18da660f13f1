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

// The gate (icp.prior_gate) and its way out (icp.prior_gate_overrule). A gate with no way out
// locks itself out: once the prior has drifted beyond it, every later match disagrees too and the
// vehicle dead-reckons for good. Matches that the gate turns away one after another, each agreeing
// with the one before (their corrections of the prediction within the gate of each other, the two
// matches' covariances together), are evidence against the prior, not the scans: after `overrule`
// of them the next such match is taken (PX4's EKF2 likewise resets to a measurement its innovation
// test has refused for too long). Wrong matches that scatter (a wall taken for its neighbour now,
// another one later) never make such a run.
class PriorGate {
 public:
  enum class Verdict { Agrees, Rejected, Overrules };

  // sigmas: the gate (0: none, every match agrees); overrule: rejections in a row before the next
  // agreeing one is taken (0: never).
  PriorGate(double sigmas, int overrule) : sigmas_(sigmas), overrule_(overrule) {}

  // distance: the match's from the prior (distance_from_prior); correction: p_match - p_predicted;
  // observed: the directions the scan fixed; match_covariance: the match's (as MatchNoise scales
  // it).
  Verdict judge(const PriorDistance& distance, const Vec3& correction,
                const Eigen::Matrix3d& observed, const Eigen::Matrix3d& match_covariance);

 private:
  double sigmas_;
  int overrule_;
  int run_ = 0;  // rejections in a row, each agreeing with the one before
  Vec3 last_correction_ = Vec3::Zero();
};

}  // namespace uavslam
