#include "slam/InertialPrior.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/Heading.hpp"

namespace uavslam {
namespace {

constexpr double kGravity = 9.80665;  // m/s^2, standard; the z bias takes up the local difference
// m; the spread given to a matched position when the scan's analysis gave none (degeneracy off).
constexpr double kDefaultScanSigma = 0.01;

bool is_finite(const ImuSample& s) {
  return std::isfinite(s.stamp) && s.orientation.coeffs().allFinite() &&
         s.linear_acceleration.allFinite();
}

Eigen::Matrix3d map_rotation(const ImuSample& sample, double heading_correction) {
  return (yaw_rotation(heading_correction) * sample.orientation.normalized()).toRotationMatrix();
}

// The accelerometer's axes the scan measures, each on its own: an axis whose direction in the map
// lies mostly (over half, as observed_basis) in the observed directions. Not the observed
// directions turned into the body (a projection that would hold a slanted mix of the axes): tilted
// a few degrees, the vertical axis leans into a blind horizontal direction, and height fixes would
// then write a bias into that axis which the blind direction integrates, unchecked, ever after.
Eigen::Matrix3d observed_body_axes(const Eigen::Matrix3d& seen, const Eigen::Matrix3d& body) {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if ((seen * body.col(i)).squaredNorm() > 0.5) axes(i, i) = 1.0;
  }
  return axes;
}

// The match's position as the state holds it: p + m (m horizontal).
Eigen::Matrix<double, 3, 11> match_of_state() {
  Eigen::Matrix<double, 3, 11> A = Eigen::Matrix<double, 3, 11>::Zero();
  A.leftCols<3>().setIdentity();
  A.block<2, 2>(0, 9).setIdentity();
  return A;
}

}  // namespace

InertialPrior::InertialPrior(const SlamConfig::Motion& noise, double max_gap)
    : noise_(noise), max_gap_(max_gap) {}

bool InertialPrior::add(const ImuSample& sample) {
  const bool in_order = samples_.empty() || sample.stamp > samples_.back().stamp;
  if (!is_finite(sample) || !in_order || sample.linear_acceleration.isZero()) {
    ++rejected_;
    return false;
  }
  samples_.push_back(sample);
  return true;
}

bool InertialPrior::add_velocity(const VelocitySample& sample) {
  const bool in_order = velocities_.empty() || sample.stamp > velocities_.back().stamp;
  const Eigen::LLT<Eigen::Matrix3d> positive(sample.covariance);
  if (!std::isfinite(sample.stamp) || !sample.velocity.allFinite() ||
      !sample.covariance.allFinite() || !in_order || positive.info() != Eigen::Success) {
    ++rejected_velocities_;
    return false;
  }
  velocities_.push_back(sample);
  return true;
}

// One sample held for dt: the mean and covariance through the equations above.
void InertialPrior::integrate(State& s, const ImuSample& sample, double dt,
                              double heading_correction) const {
  if (dt <= 0.0) return;
  const Eigen::Matrix3d R = map_rotation(sample, heading_correction);
  const Vec3 a = R * (sample.linear_acceleration - s.x.segment<3>(6)) - kGravity * Vec3::UnitZ();
  s.x.segment<3>(0) += s.x.segment<3>(3) * dt + 0.5 * a * dt * dt;
  s.x.segment<3>(3) += a * dt;
  StateMatrix F = StateMatrix::Identity();
  F.block<3, 3>(0, 3) = Eigen::Matrix3d::Identity() * dt;
  F.block<3, 3>(0, 6) = -0.5 * R * dt * dt;
  F.block<3, 3>(3, 6) = -R * dt;
  s.P = F * s.P * F.transpose();
  const double accel = noise_.accel_noise_density * noise_.accel_noise_density * dt;
  const double walk = noise_.accel_bias_walk * noise_.accel_bias_walk * dt;
  s.P.block<3, 3>(3, 3).diagonal().array() += accel;
  s.P.block<3, 3>(6, 6).diagonal().array() += walk;
}

// The matches' shared error m over the distance d flown from `from` (first-order Gauss-Markov in
// distance, not time: hovering, the scan sees the same map and m stays):
//   m' = phi m,  P_mm' = phi^2 P_mm + (1 - phi^2) sigma_m^2 I,  phi = exp(-d / D)
void InertialPrior::decorrelate(State& s, const Vec3& from) const {
  const double sigma = noise_.match_error_sigma;
  s.fresh_shared_variance = 0.0;
  if (sigma <= 0.0) return;
  const double phi = std::exp(-(s.x.segment<3>(0) - from).norm() / noise_.match_error_distance);
  s.x.segment<2>(9) *= phi;
  s.P.block<11, 2>(0, 9) *= phi;
  s.P.block<2, 11>(9, 0) *= phi;
  s.fresh_shared_variance = (1.0 - phi * phi) * sigma * sigma;
  s.P.block<2, 2>(9, 9).diagonal().array() += s.fresh_shared_variance;
}

// The state at the last posed scan carried to t through the samples since, each held until the
// next, and updated by the velocities stamped on the way; none across a gap of more than max_gap
// without a sample.
std::optional<InertialPrior::State> InertialPrior::propagated(double t,
                                                              double heading_correction) const {
  if (!state_ || samples_.empty()) return std::nullopt;
  State s = *state_;
  auto next = std::upper_bound(samples_.begin(), samples_.end(), s.stamp,
                               [](double stamp, const ImuSample& x) { return stamp < x.stamp; });
  const ImuSample* held = next == samples_.begin() ? &*next : &*std::prev(next);
  auto velocity =
      std::upper_bound(velocities_.begin(), velocities_.end(), s.stamp,
                       [](double stamp, const VelocitySample& x) { return stamp < x.stamp; });
  while (s.stamp < t) {
    double until = next != samples_.end() && next->stamp < t ? next->stamp : t;
    if (velocity != velocities_.end() && velocity->stamp < until) until = velocity->stamp;
    if (until - held->stamp > max_gap_ || held->stamp - s.stamp > max_gap_) return std::nullopt;
    integrate(s, *held, until - s.stamp, heading_correction);
    s.stamp = until;
    if (velocity != velocities_.end() && velocity->stamp <= s.stamp) {
      update_velocity(s, *velocity++, heading_correction);
    }
    if (next != samples_.end() && next->stamp <= s.stamp) held = &*next++;
  }
  decorrelate(s, state_->x.segment<3>(0));
  return s;
}

MotionPrediction InertialPrior::motion_to(double t, double heading_correction) {
  const std::optional<State> s = propagated(t, heading_correction);
  if (!s) {
    ++without_prior_;
    return {};
  }
  ++with_prior_;
  // The pipeline turns the prediction by the heading correction: hand it back unturned.
  const Eigen::Matrix3d back = yaw_rotation(-heading_correction).toRotationMatrix();
  MotionPrediction prediction;
  const Eigen::Matrix<double, 3, 11> A = match_of_state();
  prediction.motion = back * A * (s->x - state_->x);
  // The shared error's fresh change is left out: the matches' learnt noise holds it already
  // (MatchNoise learns from the innovations, which see it), and counted twice it would teach
  // MatchNoise that the matches err less than they do.
  Eigen::Matrix3d covariance = A * s->P * A.transpose();
  covariance.diagonal().head<2>().array() -= s->fresh_shared_variance;
  prediction.covariance = back * covariance * back.transpose();
  return prediction;
}

void InertialPrior::start(const ScanReport& report) {
  State s;
  s.stamp = report.pose.stamp;
  s.x.segment<3>(0) = report.pose.position;
  s.P.block<3, 3>(0, 0) = report.covariance;
  s.P.block<3, 3>(3, 3).diagonal().setConstant(noise_.initial_speed_sigma *
                                               noise_.initial_speed_sigma);
  s.P.block<3, 3>(6, 6).diagonal().setConstant(noise_.initial_bias_sigma *
                                               noise_.initial_bias_sigma);
  s.P.block<2, 2>(9, 9).diagonal().setConstant(noise_.match_error_sigma * noise_.match_error_sigma);
  state_ = s;
}

// The matched position, measured along the directions the scan fixed.
void InertialPrior::update(State& s, const ScanReport& report) const {
  const Eigen::MatrixXd E = observed_basis(report.seen.observed);
  if (E.cols() == 0) return;
  Eigen::Matrix3d scan = report.seen.covariance;
  if (scan.isZero()) scan = kDefaultScanSigma * kDefaultScanSigma * Eigen::Matrix3d::Identity();
  const Eigen::Matrix<double, 3, 11> A = match_of_state();
  const Eigen::MatrixXd H = E.transpose() * A;
  const Eigen::MatrixXd Rz = E.transpose() * scan * E;
  const Eigen::VectorXd innovation = E.transpose() * (report.pose.position - A * s.x);
  const Eigen::MatrixXd S = H * s.P * H.transpose() + Rz;
  // The gain is kept out of the blind directions (a Schmidt, "consider", update): what the scan
  // measured along a direction tilted from a blind one by noise in the normals is no measurement
  // of the blind one, however sure the scan is and however unsure the state is there.
  const Eigen::Matrix3d seen = report.seen.observed;
  const Eigen::Matrix3d body = report.pose.orientation.toRotationMatrix();
  StateMatrix keep = StateMatrix::Zero();
  keep.block<3, 3>(0, 0) = seen;
  keep.block<3, 3>(3, 3) = seen;
  keep.block<3, 3>(6, 6) = observed_body_axes(seen, body);
  keep.block<2, 2>(9, 9) = seen.topLeftCorner<2, 2>();
  const Eigen::MatrixXd K = keep * s.P * H.transpose() * S.inverse();
  s.x += K * innovation;
  // Joseph form: right for any gain, and stays symmetric and positive however small Rz is. The
  // gain takes the match's own covariance (H^-1 sigma^2), so the filter follows the matches
  // closely, as the fixed-count ICP needs to start near home (a trial fed the learnt one and
  // smoothed the matches' correlated errors: demo 0.038 m, docs/algorithm.md). But the matches err
  // as MatchNoise learnt (report.covariance, several times more), and that is what the state
  // carries on: a prediction's covariance as small as the match's own would put the innovations
  // all on the match, and the learnt scale would take the prediction's error for the match's.
  // The odometry prior takes report.covariance too.
  const StateMatrix IKH = StateMatrix::Identity() - K * H;
  const Eigen::MatrixXd learnt =
      report.covariance.isZero() ? Rz : Eigen::MatrixXd(E.transpose() * report.covariance * E);
  s.P = IKH * s.P * IKH.transpose() + K * learnt * K.transpose();
}

// The velocity source's sample, turned into the map frame by the heading correction.
void InertialPrior::update_velocity(State& s, const VelocitySample& sample,
                                    double heading_correction) const {
  const Eigen::Matrix3d R = yaw_rotation(heading_correction).toRotationMatrix();
  Eigen::Matrix<double, 3, 11> H = Eigen::Matrix<double, 3, 11>::Zero();
  H.block<3, 3>(0, 3) = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d Rz = R * sample.covariance * R.transpose();
  const Vec3 innovation = R * sample.velocity - s.x.segment<3>(3);
  const Eigen::Matrix3d S = H * s.P * H.transpose() + Rz;
  const Eigen::Matrix<double, 11, 3> K = s.P * H.transpose() * S.inverse();
  s.x += K * innovation;
  const StateMatrix IKH = StateMatrix::Identity() - K * H;
  s.P = IKH * s.P * IKH.transpose() + K * Rz * K.transpose();
}

void InertialPrior::scan_posed(const ScanReport& report, double heading_correction) {
  const double t = report.pose.stamp;
  std::optional<State> s = state_ ? propagated(t, heading_correction) : std::nullopt;
  if (!s) {
    start(report);
  } else {
    if (report.accepted()) update(*s, report);
    state_ = s;
  }
  // The sample held at t stays: the next interval starts with it. The velocities up to t are in
  // the state now.
  while (samples_.size() > 1 && samples_[1].stamp <= t) samples_.pop_front();
  while (!velocities_.empty() && velocities_.front().stamp <= t) velocities_.pop_front();
}

Vec3 InertialPrior::velocity() const {
  return state_ ? Vec3(state_->x.segment<3>(3)) : Vec3::Zero();
}

Eigen::Matrix3d InertialPrior::velocity_covariance() const {
  return state_ ? Eigen::Matrix3d(state_->P.block<3, 3>(3, 3)) : Eigen::Matrix3d::Zero();
}

Vec3 InertialPrior::bias() const {
  return state_ ? Vec3(state_->x.segment<3>(6)) : Vec3::Zero();
}

void InertialPrior::reanchor(const Eigen::Isometry3d& correction) {
  if (!state_) return;
  const Eigen::Matrix3d R = correction.linear();
  const Vec3 position = state_->x.segment<3>(0);
  state_->x.segment<3>(0) = correction * position;
  state_->x.segment<3>(3) = R * state_->x.segment<3>(3);
  state_->x.segment<2>(9) = R.topLeftCorner<2, 2>() * state_->x.segment<2>(9);
  StateMatrix G = StateMatrix::Identity();
  G.block<3, 3>(0, 0) = R;
  G.block<3, 3>(3, 3) = R;
  G.block<2, 2>(9, 9) = R.topLeftCorner<2, 2>();
  state_->P = G * state_->P * G.transpose();
}

}  // namespace uavslam
