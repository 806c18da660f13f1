// The motion prior from the IMU's accelerations (icp.motion_prior: imu): between scans, the
// specific force is integrated in the map frame (a strapdown INS, zero-order hold per sample), and
// each matched pose corrects it, in the directions the scan fixed, through a linear Kalman filter
// over position, velocity and the accelerometer's bias (FAST-LIO and LIO-SAM carry the motion the
// same way; their filters also hold the attitude, which here the orientation source gives):
//   a  = R (f - b) - g                   f: specific force (body), R: orientation (heading-
//                                        corrected), g = (0, 0, 9.80665): the bias absorbs any
//                                        local difference of gravity
//   p' = p + v dt + a dt^2 / 2,   v' = v + a dt,   b' = b + bias walk
//   F  = [I  I dt  -R dt^2/2;  0  I  -R dt;  0  0  I],  Q = diag(0, s_a^2 dt I, s_b^2 dt I)
// A match errs by its own noise and by a part m it shares with the matches around it (the few
// structures that fix a weak direction, each placed in the map from a handful of returns; a
// cabinet's top a climbing scan grazes): taken as independent, a few seconds of matches drifting
// by a centimetre read as an acceleration, and the bias they write is flown on, sure of itself,
// through the blind stretch after (furnished_corridor.yaml). So m, horizontal (the height comes
// from the floor, one surface), is a fourth state, a Gauss-Markov process over the distance flown
// (motion.match_error_sigma, _distance; 0: none):
//   m' = phi m,  phi = exp(-d / D),  Q_m = (1 - phi^2) sigma_m^2 I
// Update at a matched scan: z = E^T p_scan, H = E^T [I 0 0 J] (J = [I_2; 0]: the match is at
// p + m), R_z = E^T Sigma_scan E, where the columns of E span the directions the scan fixed
// (ScanReport::seen): a blind direction neither corrects the state nor is corrected by it. The gain
// takes the match's own Sigma_scan, the covariance (Joseph form) the error the match really has,
// as MatchNoise learnt it. So the bias and velocity are estimated from the matched poses wherever
// the walls allow, and carry the vehicle through where they do not. A third source, the autopilot's
// velocity (motion.fuse_velocity), updates the velocity at each of its samples: z = R_h v_source, H
// = [0 I 0 0], R_z = R_h Sigma_v R_h^T (R_h: the heading correction). Where the scan is blind the
// position then drifts with the velocity's noise, integrated, instead of with an accelerometer bias
// nothing observes (1/2 b t^2).
#pragma once

#include <cstddef>
#include <deque>
#include <optional>

#include "core/MotionPrediction.hpp"
#include "core/SlamConfig.hpp"
#include "core/SlamPipeline.hpp"

namespace uavslam {

class InertialPrior {
 public:
  // max_gap: a scan whose time is farther than this from the last IMU sample gets no prediction.
  InertialPrior(const SlamConfig::Motion& noise, double max_gap);

  // False (counted in rejected()) for a non-finite or out-of-order sample, or one without a
  // specific force (a source that gives only the attitude, e.g. a 2D log's odometry heading).
  bool add(const ImuSample& sample);
  // False (counted in rejected_velocities()) for a non-finite or out-of-order sample, or one
  // whose covariance is not positive definite (a source that states no accuracy).
  bool add_velocity(const VelocitySample& sample);

  // The motion from the last posed scan to the scan stamped t, in the orientation source's frame
  // (heading_correction: what the matcher has added to the source's heading), with the predicted
  // position's covariance. None before the first posed scan or across a gap in the samples.
  MotionPrediction motion_to(double t, double heading_correction);
  // The scan got a pose: the filter moves to it and, if the scan was matched, takes its position.
  void scan_posed(const ScanReport& report, double heading_correction);

  // The map frame moved under the filter (the back end re-anchored the map on an optimised pose
  // graph): the position and velocity move with it; the bias is the body's and stays.
  void reanchor(const Eigen::Isometry3d& correction);

  std::size_t scans_with_prior() const { return with_prior_; }
  std::size_t scans_without_prior() const { return without_prior_; }
  std::size_t rejected() const { return rejected_; }
  std::size_t rejected_velocities() const { return rejected_velocities_; }
  Vec3 velocity() const;  // m/s in the map frame (zero before the first posed scan)
  Eigen::Matrix3d velocity_covariance() const;  // (m/s)^2
  Vec3 bias() const;                            // m/s^2 in the body frame

 private:
  using StateVector = Eigen::Matrix<double, 11, 1>;  // p, v, b, m (horizontal)
  using StateMatrix = Eigen::Matrix<double, 11, 11>;
  struct State {
    double stamp = 0.0;
    StateVector x = StateVector::Zero();
    StateMatrix P = StateMatrix::Zero();
    double fresh_shared_variance = 0.0;  // m^2: what m gained since the last posed scan
  };

  std::optional<State> propagated(double t, double heading_correction) const;
  void integrate(State& state, const ImuSample& sample, double dt, double heading_correction) const;
  void decorrelate(State& state, const Vec3& from) const;
  void update(State& state, const ScanReport& report) const;
  void update_velocity(State& state, const VelocitySample& sample, double heading_correction) const;
  void start(const ScanReport& report);

  SlamConfig::Motion noise_;
  double max_gap_;
  std::deque<ImuSample> samples_;
  std::deque<VelocitySample> velocities_;  // after the last posed scan
  std::optional<State> state_;             // at the last posed scan
  std::size_t with_prior_ = 0;
  std::size_t without_prior_ = 0;
  std::size_t rejected_ = 0;
  std::size_t rejected_velocities_ = 0;
};

}  // namespace uavslam
