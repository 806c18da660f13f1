// How noisy the matches really are (beyond the seed). The information the pairs give
// (ScanInformation) assumes every pair's error independent; a scan's errors are not (the map's
// point spacing, the normals, a few wrong pairs), and H^-1 sigma^2 is several times too confident.
// The innovations say by how much: at a matched scan, the correction of the motion prior's
// prediction has the covariance S = s Sigma_scan + Sigma_predicted, and when s is right its
// squared Mahalanobis distance d^2 (PriorAgreement) has the mean m, the directions observed
// (chi-square). So s follows the innovations (adaptive estimation, Mehra 1970; a stochastic
// approximation of E[d^2 / m] = 1):
//   log s <- log s + rate (min(d^2 / m, cap) - 1),   s >= 1
// (the cap: one wild match moves it no more than a few ordinary ones). It learns each building's
// noise as it flies; no figure is tuned to one.
#pragma once

#include <cmath>

#include "core/extensions/PriorAgreement.hpp"

namespace uavslam {

class MatchNoise {
 public:
  // The scale by which the match's own covariance (H^-1 sigma^2) is multiplied; 1 at first.
  double scale() const { return std::exp(log_scale_); }

  // An accepted match's distance from the prior, measured with the current scale.
  void add(const PriorDistance& distance);

 private:
  double log_scale_ = 0.0;
};

}  // namespace uavslam
