// How noisy the matches really are (beyond the seed). The information the pairs give
// (ScanInformation) assumes every pair's error independent; a scan's errors are not (the map's
// point spacing, the normals, a few wrong pairs), and H^-1 sigma^2 is several times too confident.
// The innovations say by how much: at a matched scan, the correction of the motion prior's
// prediction has the covariance S = s Sigma_scan + Sigma_predicted, and when s is right its
// squared Mahalanobis distance d^2 (PriorAgreement) has the mean m, the directions observed
// (chi-square). So s follows the innovations (adaptive estimation, Mehra 1970; a stochastic
// approximation of E[d^2 / m] = 1):
//   log s <- log s + rate (min(d^2 / m, cap) - 1)
// (the cap: one wild match moves it no more than a few ordinary ones), either way: H^-1 sigma^2 can
// be too cautious as well, where sigma^2 counts pairs the robust refinement set aside (a thin
// wall's other face 0.3 m away), and s then learns to be below 1. The horizontal directions
// (the level beams against the walls) and the vertical one (the floor beams) are two sensors with
// their own noise, and each has its own s, learnt from its own part of the innovation. It learns
// each building's noise as it flies; no figure is tuned to one.
#pragma once

#include <cmath>
#include <cstddef>

#include "core/Types.hpp"
#include "core/extensions/PriorAgreement.hpp"

namespace uavslam {

class MatchNoise {
 public:
  // The scales by which the match's own covariance (H^-1 sigma^2) is multiplied; 1 at first.
  double horizontal_scale() const { return std::exp(log_horizontal_); }
  double vertical_scale() const { return std::exp(log_vertical_); }

  // The match's covariance as the innovations say it is: Sigma_scan with its horizontal block
  // times the horizontal scale and its vertical one times the vertical scale.
  Eigen::Matrix3d scaled(const Eigen::Matrix3d& match_covariance) const;

  // An accepted match: its correction of the prediction, the directions it observed, its own
  // covariance (unscaled) and the prediction's.
  void add(const Vec3& correction, const Eigen::Matrix3d& observed,
           const Eigen::Matrix3d& match_covariance, const Eigen::Matrix3d& predicted_covariance);

  // Enough matches learnt from for the scales to have settled (about 1 / rate of them): before,
  // a distance measured with them says little.
  bool settled() const;

 private:
  std::size_t added_ = 0;
  double log_horizontal_ = 0.0;
  double log_vertical_ = 0.0;
};

}  // namespace uavslam
