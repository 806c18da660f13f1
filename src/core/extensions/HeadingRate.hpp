// How fast the orientation source's heading drifts (beyond the seed): an autopilot's yaw without a
// magnetometer walks off with its gyro's bias, degrees per minute, and every keyframe made
// meanwhile joins the map turned by it. Checked against the map (icp.heading: periodic_check), the
// drift shows, but only against old map: a check against the last keyframes sees the drift since
// they were made, seconds' worth, under heading_check_tolerance; the map turns along with the
// vehicle until it comes back to old map (yaw_drift.yaml).
//
// A check at t against map made, on average, at t_map (its keyframes' times weighted by their
// share of the heading, MapUncertainty::heading_shares) measures the drift over the span
// dt = t - t_map. With H the heading correction the pipeline applied (at t, and when each
// keyframe was made, the same weighting) and d the check's disagreement (the turn it wants),
//   m = d + H(t) - H(t_map) = c + r dt + noise
// whatever was applied in between: r is the rate at which the correction has to grow to hold
// the heading still on the map, c how far the heading is off the map whatever the span (a check
// that finds it under heading_check_tolerance leaves it there). A drift grows with the span, an
// offset does not: a line through checks of like spans would take a steady 0.1 degree offset
// for 2 degrees a minute (demo.yaml, seed 7). The line is fitted by least squares over the
// checks, the rate against a prior r ~ N(0, sigma_r^2) (imu.heading_drift_sigma), the noise
// sigma_d^2 the line's residual variance:
//   r = S_tm / (S_tt + sigma_d^2 / sigma_r^2),   S_tt = sum (dt - mean dt)^2,
//   S_tm = sum (dt - mean dt)(m - mean m)
// with the standard error sigma_d / sqrt(S_tt + sigma_d^2 / sigma_r^2). A rate within three of
// them, or from fewer than 30 checks, is taken as none. The pipeline adds r dt to the correction
// at every scan (the gyro-bias estimate of a LiDAR-inertial filter, here learnt from the map
// alone), and feeds this only checks made before keyframes whose scan the gate on the prior let
// through.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace uavslam {

class HeadingRate {
 public:
  // prior_sigma: sigma_r above (rad/s); 0: no drift is ever learnt.
  explicit HeadingRate(double prior_sigma) : prior_sigma_(prior_sigma) {}

  // A check: its disagreement d (rad), the span dt = t - t_map (s) and the correction applied
  // over it, H(t) - H(t_map) (rad). Spans that are not positive say nothing of a rate.
  void add_check(double disagreement, double span, double applied);

  // r above (rad/s); 0 before 30 checks, without a prior, or while within three standard
  // errors.
  double rate() const;

  // The keyframes made before the rate was learnt, or while a smaller one was followed, joined
  // the map turned by the drift not followed then. Keyframe k, made at t_k with the correction
  // H_k, should have had H_0 + r (t_k - t_0) (the first keyframe anchors the map's heading):
  //   turn_k = r (t_k - t_0) - (H_k - H_0)
  // (rad, one per keyframe; all 0 until the rate is beyond five standard errors, a stricter test
  // than following it: the map is not turned on noise).
  std::vector<double> turns(const std::vector<double>& stamps,
                            const std::vector<double>& corrections) const;

  // The line as it stands, for the map's covariance (MapUncertainty): its rate, however few
  // standard errors, and the variance of that rate's error (rad/s, rad^2/s^2), from the third
  // check on (without a prior too: then the line alone, which nobody follows); before, 0 and
  // sigma_r^2. A keyframe made dt after the first with the correction H (since the first's) is
  // off by r_true dt - H: the rate's error is one for all keyframes, so as the checks pin it down
  // the whole map's heading is surer, the early keyframes' too, and the part of the drift the
  // line knows of but nobody applied shows.
  struct Estimate {
    double rate = 0.0;
    double variance = 0.0;
  };
  Estimate estimate() const;

 private:
  struct Fit {
    double rate = 0.0;   // r above
    double sigma = 0.0;  // its standard error
  };
  // The line through the checks (against the prior, if any); none before min_checks of them or
  // without a span.
  std::optional<Fit> fit(std::size_t min_checks) const;
  // The line rate() and turns() act on.
  std::optional<Fit> followed_fit() const;

  double prior_sigma_;
  // Over the checks: their count and the sums of dt, m, dt^2, dt m and m^2.
  std::size_t n_ = 0;
  double t_ = 0.0;
  double m_ = 0.0;
  double tt_ = 0.0;
  double tm_ = 0.0;
  double mm_ = 0.0;
};

}  // namespace uavslam
