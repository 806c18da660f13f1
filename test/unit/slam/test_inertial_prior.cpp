#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <gtest/gtest.h>

#include "sim/ImuSimulator.hpp"
#include "sim/Trajectory.hpp"
#include "slam/InertialPrior.hpp"

namespace uavslam {
namespace {

constexpr double kScanPeriod = 0.025;     // s, 40 Hz
constexpr double kImuPeriod = 0.005;      // s, 200 Hz
constexpr double kVelocityPeriod = 0.05;  // s, 20 Hz

// A flight that speeds up, turns and climbs: from rest at (0, 0, 1) to (6, 3, 1.8) in 6 s.
sim::Trajectory flight() {
  return sim::Trajectory(
      {{0.0, Vec3(0, 0, 1), 0.0}, {3.0, Vec3(2.5, 0.5, 1.2), 30.0}, {6.0, Vec3(6, 3, 1.8), 60.0}});
}

sim::ImuSpec noiseless() {
  sim::ImuSpec spec;
  spec.orientation_noise_std_deg = 0.0;
  spec.gyro_noise_std = 0.0;
  spec.accel_noise_std = 0.0;
  return spec;
}

// A scan's report at the true pose: matched, seeing `observed` of it.
ScanReport report_at(const sim::Trajectory& trajectory, double t,
                     const Eigen::Matrix3d& observed = Eigen::Matrix3d::Identity(),
                     const Vec3& error = Vec3::Zero()) {
  ScanReport r;
  r.outcome = ScanOutcome::Accepted;
  r.pose = trajectory.pose_at(t);
  r.pose.position += error;
  r.seen.observed = observed;
  r.seen.covariance = 1e-6 * observed;
  r.covariance = r.seen.covariance;
  return r;
}

struct Flight {
  sim::Trajectory trajectory = flight();
  sim::ImuSimulator imu{noiseless(), 1};
  InertialPrior prior{SlamConfig::Motion{}, 0.1};
  double fed_until = -1.0;
  Vec3 bias = Vec3::Zero();    // added to every sample's specific force
  bool with_velocity = false;  // a velocity source's samples, true, stated to 5 cm/s, at 20 Hz
  double velocity_fed_until = 0.0;

  void feed_to(double t) {
    for (double s = fed_until + kImuPeriod; s <= t + 1e-9; s += kImuPeriod) {
      ImuSample sample = imu.sample_at(trajectory, std::max(s, 0.0));
      sample.linear_acceleration += bias;
      prior.add(sample);
      fed_until = s;
    }
    for (double s = velocity_fed_until + kVelocityPeriod; with_velocity && s <= t + 1e-9;
         s += kVelocityPeriod) {
      prior.add_velocity({s, trajectory.velocity_at(s), 0.05 * 0.05 * Eigen::Matrix3d::Identity()});
      velocity_fed_until = s;
    }
  }

  // The first scan, posed at the truth, with the samples up to it.
  void start() {
    fed_until = -kImuPeriod;
    feed_to(0.0);
    prior.scan_posed(report_at(trajectory, 0.0), 0.0);
  }

  // Every scan up to `end`: predicted, then posed as `scan(t)` reports it.
  void fly_to(double end, const std::function<ScanReport(double)>& scan) {
    for (double t = kScanPeriod; t <= end + 1e-9; t += kScanPeriod) {
      feed_to(t);
      prior.motion_to(t, 0.0);
      prior.scan_posed(scan(t), 0.0);
    }
  }
};

// Preintegration: the specific force, turned by the attitude, less gravity, integrated twice from
// the first pose, gives the true motion.
TEST(InertialPrior, IntegratesTheSimulatorsTrueMotion) {
  Flight f;
  f.fed_until = -kImuPeriod;
  f.feed_to(0.0);
  EXPECT_FALSE(f.prior.motion_to(0.0, 0.0).covariance) << "nothing posed yet";
  f.prior.scan_posed(report_at(f.trajectory, 0.0), 0.0);
  f.feed_to(3.0);
  const MotionPrediction p = f.prior.motion_to(3.0, 0.0);
  ASSERT_TRUE(p.covariance);
  const Vec3 truth = f.trajectory.pose_at(3.0).position - f.trajectory.pose_at(0.0).position;
  EXPECT_LT((p.motion - truth).norm(), 0.01) << p.motion.transpose() << " vs " << truth.transpose();
  EXPECT_GT((*p.covariance)(0, 0), 0.0);
}

// A bias the filter did not know of is found from the matched poses, and the velocity with it.
TEST(InertialPrior, MatchedPosesEstimateTheBiasAndTheVelocity) {
  Flight f;
  f.bias = Vec3(0.05, -0.03, 0.08);
  f.start();
  f.fly_to(6.0, [&](double t) { return report_at(f.trajectory, t); });
  EXPECT_LT((f.prior.bias() - f.bias).norm(), 0.01) << f.prior.bias().transpose();
  EXPECT_LT((f.prior.velocity() - f.trajectory.velocity_at(6.0)).norm(), 0.01);
}

// The gain follows the matches as their own covariance says (H^-1 sigma^2, 1 mm here), but the
// prediction's covariance is what the matches really err by, as MatchNoise learnt it (report.
// covariance, 25 times the variance here): the state carries on the match's 5 mm, not its 1 mm.
// The same flight, the same (true) matches: the motion predicted as well, the covariance grown.
TEST(InertialPrior, ThePredictionCarriesTheErrorTheMatchesReallyHave) {
  const auto predicted = [](double learnt_scale) {
    Flight f;
    f.start();
    f.fly_to(3.0, [&](double t) {
      ScanReport r = report_at(f.trajectory, t);
      r.covariance = learnt_scale * r.seen.covariance;
      return r;
    });
    f.feed_to(3.0 + kScanPeriod);
    return f.prior.motion_to(3.0 + kScanPeriod, 0.0);
  };
  const MotionPrediction own = predicted(1.0);
  const MotionPrediction learnt = predicted(25.0);
  ASSERT_TRUE(own.covariance && learnt.covariance);
  Flight truth;
  const Vec3 step =
      truth.trajectory.pose_at(3.0 + kScanPeriod).position - truth.trajectory.pose_at(3.0).position;
  EXPECT_LT((learnt.motion - step).norm(), 1e-3);
  EXPECT_LT((own.motion - step).norm(), 1e-3);
  EXPECT_GT((*learnt.covariance)(0, 0), 10.0 * (*own.covariance)(0, 0));
  EXPECT_GT((*learnt.covariance)(0, 0), 1e-6);  // at least a match's own millimetre
}

// Matches that drift together by 2 cm over their last second (a structure's top grazed by a
// climbing scan), then the scans go blind along x (a corridor's axis). Taken as independent, the
// drift is read as an acceleration the IMU never felt, and the velocity it writes is flown on
// through the blind stretch, sure of itself. With the matches' shared error a state of its own
// (motion.match_error_sigma), the same seconds of matches tell less of the velocity, and the
// filter says so: its error is within the spread it states.
TEST(InertialPrior, ADriftSharedByTheMatchesLeavesTheVelocityAsUnsureAsItIs) {
  const auto velocity_sigmas = [](double shared_sigma) {
    Flight f;
    SlamConfig::Motion noise;
    noise.match_error_sigma = shared_sigma;
    f.prior = InertialPrior(noise, 0.1);
    f.start();
    const Eigen::Matrix3d blind_x = Eigen::Vector3d(0, 1, 1).asDiagonal();
    f.fly_to(6.0, [&](double t) {
      if (t > 3.0) return report_at(f.trajectory, t, blind_x);
      const double drift = 0.02 * std::clamp(t - 2.0, 0.0, 1.0);
      ScanReport r = report_at(f.trajectory, t, Eigen::Matrix3d::Identity(), Vec3(drift, 0, 0));
      r.seen.covariance *= 25.0;  // 5 mm, as a fix on a few structures is stated
      r.covariance = r.seen.covariance;
      return r;
    });
    const double error = f.prior.velocity().x() - f.trajectory.velocity_at(6.0).x();
    return std::abs(error) / std::sqrt(f.prior.velocity_covariance()(0, 0));
  };
  const double independent = velocity_sigmas(0.0);
  const double shared = velocity_sigmas(0.01);
  EXPECT_GT(independent, 3.0) << "sure of a velocity the drift wrote";
  EXPECT_LT(shared, 3.0);
}

// A matched pose says nothing of a direction the scan could not see: a 1 m error along it does not
// pull the state, which stays with the integrated motion.
TEST(InertialPrior, ABlindDirectionIsNeitherMeasuredNorPulled) {
  Flight f;
  f.start();
  const Eigen::Matrix3d blind_x = Eigen::Vector3d(0, 1, 1).asDiagonal();
  f.fly_to(3.0, [&](double t) { return report_at(f.trajectory, t, blind_x, Vec3(1.0, 0, 0)); });
  f.feed_to(3.0 + kScanPeriod);
  const MotionPrediction p = f.prior.motion_to(3.0 + kScanPeriod, 0.0);
  ASSERT_TRUE(p.covariance);
  // The step predicted from 3.0 matches the truth: the velocity along x was not pulled by the
  // wrong x, and the uncertainty along x has grown while that along y stayed small.
  const Vec3 truth =
      f.trajectory.pose_at(3.0 + kScanPeriod).position - f.trajectory.pose_at(3.0).position;
  EXPECT_LT(std::abs(p.motion.x() - truth.x()), 0.002);
  EXPECT_GT((*p.covariance)(0, 0), 100.0 * (*p.covariance)(1, 1));
}

// Tilted to accelerate, the accelerometer's forward axis leans into the height the scan fixes; an
// error in those height fixes is still no measurement of that axis's bias, which the blind forward
// direction would integrate unchecked: it stays where it started (zero), however the height errs.
TEST(InertialPrior, HeightFixesWriteNoBiasIntoABlindAxis) {
  Flight f;
  // Down a corridor's axis (x), facing along it, speeding up and slowing down: pitched throughout.
  f.trajectory = sim::Trajectory(
      {{0.0, Vec3(0, 0, 1), 0.0}, {3.0, Vec3(3, 0, 1.2), 0.0}, {6.0, Vec3(5, 0, 1.1), 0.0}});
  f.start();
  const Eigen::Matrix3d blind_x = Eigen::Vector3d(0, 1, 1).asDiagonal();
  f.fly_to(6.0, [&](double t) {
    return report_at(f.trajectory, t, blind_x, Vec3(0.0, 0.0, 0.02 * std::sin(t)));
  });
  EXPECT_LT(std::abs(f.prior.bias().x()), 1e-6) << f.prior.bias().transpose();
  EXPECT_GT(std::abs(f.prior.bias().z()), 1e-4) << "the height errors are taken as a bias there";
}

// Down a corridor's axis (x), blind along it, with an accelerometer bias along it that nothing
// observes: alone, the IMU's velocity errs by b t (0.18 m/s after 6 s, the position by b t^2 / 2);
// with the autopilot's velocity (the third motion source) it stays within the velocity's noise.
TEST(InertialPrior, AVelocitySourceCarriesABlindAxisThatABiasedAccelerometerLoses) {
  const auto velocity_error = [](bool with_velocity) {
    Flight f;
    f.trajectory = sim::Trajectory(
        {{0.0, Vec3(0, 0, 1), 0.0}, {3.0, Vec3(3, 0, 1.2), 0.0}, {6.0, Vec3(5, 0, 1.1), 0.0}});
    f.bias = Vec3(0.03, 0.0, 0.0);
    f.with_velocity = with_velocity;
    f.start();
    const Eigen::Matrix3d blind_x = Eigen::Vector3d(0, 1, 1).asDiagonal();
    f.fly_to(6.0, [&](double t) { return report_at(f.trajectory, t, blind_x); });
    return (f.prior.velocity() - f.trajectory.velocity_at(6.0)).norm();
  };
  EXPECT_GT(velocity_error(false), 0.1);
  EXPECT_LT(velocity_error(true), 0.03);
}

TEST(InertialPrior, RefusesVelocitiesItCannotFuse) {
  InertialPrior prior(SlamConfig::Motion{}, 0.1);
  const Eigen::Matrix3d stated = 0.01 * Eigen::Matrix3d::Identity();
  EXPECT_TRUE(prior.add_velocity({1.0, Vec3(1, 0, 0), stated}));
  EXPECT_FALSE(prior.add_velocity({0.9, Vec3(1, 0, 0), stated})) << "out of order";
  EXPECT_FALSE(prior.add_velocity({1.1, Vec3(std::nan(""), 0, 0), stated}));
  EXPECT_FALSE(prior.add_velocity({1.2, Vec3(1, 0, 0), Eigen::Matrix3d::Zero()}))
      << "a source that states no accuracy";
  EXPECT_TRUE(prior.add_velocity({1.3, Vec3(1, 0, 0), stated}));
  EXPECT_EQ(prior.rejected_velocities(), 3u);
}

TEST(InertialPrior, RefusesSamplesItCannotIntegrate) {
  InertialPrior prior(SlamConfig::Motion{}, 0.1);
  ImuSample good;
  good.stamp = 1.0;
  good.linear_acceleration = Vec3(0, 0, 9.8);
  EXPECT_TRUE(prior.add(good));
  ImuSample attitude_only = good;
  attitude_only.stamp = 1.1;
  attitude_only.linear_acceleration = Vec3::Zero();
  EXPECT_FALSE(prior.add(attitude_only)) << "a source without an accelerometer";
  ImuSample late = good;
  late.stamp = 0.9;
  EXPECT_FALSE(prior.add(late));
  ImuSample broken = good;
  broken.stamp = 1.2;
  broken.linear_acceleration.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(prior.add(broken));
  EXPECT_EQ(prior.rejected(), 3u);
}

// A gap in the samples longer than max_gap: no prediction rather than one from a stale sample.
TEST(InertialPrior, GivesNoPredictionAcrossAGapInTheSamples) {
  Flight f;
  f.start();
  const MotionPrediction p = f.prior.motion_to(0.5, 0.0);
  EXPECT_FALSE(p.covariance);
  EXPECT_EQ(p.motion, Vec3::Zero());
  EXPECT_EQ(f.prior.scans_without_prior(), 1u);
}

}  // namespace
}  // namespace uavslam
