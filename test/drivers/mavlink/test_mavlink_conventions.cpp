// Our ENU/FLU frames against the autopilots' NED/FRD, written from first principles (which way is
// north, which wing goes down), the autopilot clock with drift and jitter, and the pose encoder.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "drivers/mavlink/AutopilotClock.hpp"
#include "drivers/mavlink/FrameConventions.hpp"
#include "drivers/mavlink/PoseEncoder.hpp"

namespace uavslam::mavlink {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

Eigen::Quaterniond about(const Eigen::Vector3d& axis, double angle) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis));
}

TEST(MavlinkFrameConventions, PositionsSwapEastNorthAndFlipUp) {
  // 1 m east, 2 m north, 3 m up is 2 m north, 1 m east, -3 m down.
  EXPECT_TRUE(ned_from_enu({1, 2, 3}).isApprox(Eigen::Vector3d(2, 1, -3)));
  EXPECT_TRUE(enu_from_ned({2, 1, -3}).isApprox(Eigen::Vector3d(1, 2, 3)));
  // Forward 1, left 2, up 3 is forward 1, right -2, down -3.
  EXPECT_TRUE(frd_from_flu({1, 2, 3}).isApprox(Eigen::Vector3d(1, -2, -3)));
  EXPECT_TRUE(flu_from_frd({1, -2, -3}).isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST(MavlinkFrameConventions, FacingNorthIsYawZeroInNed) {
  // ENU yaw +90 deg: body x (forward) along world +y, north.
  const Eigen::Quaterniond north_enu = about(Eigen::Vector3d::UnitZ(), 90 * kDeg);
  EXPECT_TRUE((north_enu * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  const EulerAngles ned = euler_zyx(ned_frd_from_enu_flu(north_enu));
  EXPECT_NEAR(ned.yaw, 0.0, 1e-12);
  EXPECT_NEAR(ned.roll, 0.0, 1e-12);
  EXPECT_NEAR(ned.pitch, 0.0, 1e-12);
  // Facing east (ENU yaw 0) is NED yaw +90 deg; facing west (ENU 180) is NED -90.
  EXPECT_NEAR(euler_zyx(ned_frd_from_enu_flu(Eigen::Quaterniond::Identity())).yaw, 90 * kDeg,
              1e-12);
  EXPECT_NEAR(euler_zyx(ned_frd_from_enu_flu(about(Eigen::Vector3d::UnitZ(), kPi))).yaw, -90 * kDeg,
              1e-12);
}

TEST(MavlinkFrameConventions, NoseUpIsPositivePitchAndRightWingDownPositiveRoll) {
  // Facing north, nose 10 deg up: forward has a +up component. In FLU that is a rotation about
  // body y (left) by -10 deg.
  const Eigen::Quaterniond nose_up =
      about(Eigen::Vector3d::UnitZ(), 90 * kDeg) * about(Eigen::Vector3d::UnitY(), -10 * kDeg);
  EXPECT_GT((nose_up * Eigen::Vector3d::UnitX()).z(), 0.0);
  EXPECT_NEAR(euler_zyx(ned_frd_from_enu_flu(nose_up)).pitch, 10 * kDeg, 1e-12);
  // Right wing 10 deg down: body y (left) gets a +up component: about body x by +10 deg.
  const Eigen::Quaterniond right_down =
      about(Eigen::Vector3d::UnitZ(), 90 * kDeg) * about(Eigen::Vector3d::UnitX(), 10 * kDeg);
  EXPECT_GT((right_down * Eigen::Vector3d::UnitY()).z(), 0.0);
  EXPECT_NEAR(euler_zyx(ned_frd_from_enu_flu(right_down)).roll, 10 * kDeg, 1e-12);
}

TEST(MavlinkFrameConventions, AHoveringAccelerometerReadsUpInFluAndMinusGInFrd) {
  const Eigen::Vector3d flu(0, 0, 9.81);  // specific force at rest, as src/sim models it
  EXPECT_TRUE(frd_from_flu(flu).isApprox(Eigen::Vector3d(0, 0, -9.81)));
}

TEST(MavlinkFrameConventions, OrientationsRoundTripAndAgreeWithVectorMaps) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Quaterniond enu_flu =
        from_euler_zyx({angle(random) / 2, angle(random) / 2, angle(random)});
    const Eigen::Quaterniond ned_frd = ned_frd_from_enu_flu(enu_flu);
    EXPECT_TRUE(enu_flu_from_ned_frd(ned_frd).isApprox(enu_flu) ||
                enu_flu_from_ned_frd(ned_frd).coeffs().isApprox(-enu_flu.coeffs()));
    // A body vector mapped either way lands on the same world direction.
    const Eigen::Vector3d body(0.3, -0.2, 0.9);
    EXPECT_TRUE((ned_frd * frd_from_flu(body)).isApprox(ned_from_enu(enu_flu * body)));
    const EulerAngles ours = euler_zyx(enu_flu);
    const EulerAngles theirs = euler_zyx(ned_frd);
    EXPECT_NEAR(theirs.roll, ours.roll, 1e-9);
    EXPECT_NEAR(theirs.pitch, -ours.pitch, 1e-9);
    EXPECT_NEAR(std::remainder(theirs.yaw - (kPi / 2 - ours.yaw), 2 * kPi), 0.0, 1e-9);
  }
}

TEST(MavlinkFrameConventions, CovarianceSwapsEastNorthAndFlipsPitchAndYawTerms) {
  Matrix6d enu = Eigen::Matrix<double, 6, 1>(1, 2, 3, 4, 5, 6).asDiagonal();
  enu(0, 5) = enu(5, 0) = 0.5;  // east error correlated with yaw error
  const Matrix6d ned = ned_frd_covariance(enu);
  EXPECT_DOUBLE_EQ(ned(0, 0), 2);  // north variance = our y variance
  EXPECT_DOUBLE_EQ(ned(1, 1), 1);
  EXPECT_DOUBLE_EQ(ned(2, 2), 3);
  EXPECT_DOUBLE_EQ(ned(4, 4), 5);
  EXPECT_DOUBLE_EQ(ned(1, 5), -0.5);  // east (NED y) with yaw, whose sign flips
  EXPECT_DOUBLE_EQ(ned(0, 5), 0.0);
}

TEST(MavlinkAutopilotClock, FollowsOffsetAndDriftThroughJitteryRoundTrips) {
  // The autopilot booted 1000 s after the host clock's zero and runs 80 ppm fast.
  const double boot = 1000.0;
  const double rate = 1.0 + 80e-6;
  const auto autopilot_ns = [&](double host) {
    return static_cast<std::int64_t>(std::llround((host - boot) * rate * 1e9));
  };
  std::mt19937 random(3);
  std::exponential_distribution<double> queueing(1.0 / 1e-3);  // 1 ms mean extra delay
  AutopilotClock clock;
  EXPECT_FALSE(clock.host_time(0).has_value());
  double worst = 0;
  for (int i = 0; i < 200; ++i) {  // 1 Hz TIMESYNC for 200 s
    const double sent = boot + 10.0 + i;
    const double out = 0.4e-3 + queueing(random);
    const double back = 0.4e-3 + queueing(random);
    clock.add_round_trip(sent, autopilot_ns(sent + out), sent + out + back);
    if (i < 20) continue;
    const double truth = sent + 0.5;
    worst = std::max(worst, std::abs(*clock.host_time(autopilot_ns(truth)) - truth));
  }
  EXPECT_LT(worst, 1e-3) << worst;
  EXPECT_NEAR(clock.drift_ppm(), -80.0, 20.0);  // host runs slow against the autopilot
  EXPECT_NEAR(clock.offset(), boot, 0.1);
}

TEST(MavlinkAutopilotClock, UsesSystemTimeUntilTheFirstRoundTrip) {
  AutopilotClock clock;
  clock.add_one_way(5'000'000'000, 105.01);  // time_boot_ms 5000 arrived at host 105.01 s
  ASSERT_TRUE(clock.synchronised());
  EXPECT_NEAR(*clock.host_time(6'000'000'000), 106.01, 1e-9);
  clock.add_round_trip(200.0, 100'000'000'000, 200.002);
  EXPECT_NEAR(*clock.host_time(100'000'000'000), 200.001, 1e-9);
  clock.add_one_way(5'000'000'000, 105.01);  // ignored once round trips exist
  EXPECT_NEAR(*clock.host_time(100'000'000'000), 200.001, 1e-9);
}

PoseEstimate estimate_at(double stamp, const Eigen::Vector3d& position, std::uint64_t seq) {
  PoseEstimate e;
  e.pose.stamp = stamp;
  e.pose.position = position;
  e.scan_seq = seq;
  return e;
}

TEST(MavlinkPoseEncoder, SendsTheMatcherPoseInNed) {
  PoseEstimate e = estimate_at(1700000000.25, {1, 2, 3}, 5);
  e.pose.orientation = about(Eigen::Vector3d::UnitZ(), 90 * kDeg);  // facing north
  for (int i = 0; i < 6; ++i) e.covariance[static_cast<std::size_t>(i * 7)] = 0.01 * (i + 1);
  const VisionPositionEstimate vpe = vision_position_estimate(e, 4);
  EXPECT_EQ(vpe.usec, 1700000000250000ull);
  EXPECT_FLOAT_EQ(vpe.x, 2);  // north
  EXPECT_FLOAT_EQ(vpe.y, 1);  // east
  EXPECT_FLOAT_EQ(vpe.z, -3);
  EXPECT_NEAR(vpe.yaw, 0.0, 1e-6);
  EXPECT_FLOAT_EQ(vpe.covariance[0], 0.02f);   // x row: (0,0) = our y variance
  EXPECT_FLOAT_EQ(vpe.covariance[6], 0.01f);   // y row starts at (1,1)
  EXPECT_FLOAT_EQ(vpe.covariance[20], 0.06f);  // (5,5): yaw
  EXPECT_EQ(vpe.reset_counter, 4);

  const Odometry odometry = mavlink::odometry(e, 4);
  EXPECT_EQ(odometry.frame_id, kMavFrameLocalNed);
  EXPECT_EQ(odometry.child_frame_id, kMavFrameBodyFrd);
  EXPECT_NEAR(odometry.q[0], 1.0, 1e-6);  // facing north, level: the identity in NED/FRD
  EXPECT_TRUE(std::isnan(odometry.vx));
  EXPECT_TRUE(std::isnan(odometry.velocity_covariance[0]));
  EXPECT_EQ(odometry.quality, 100);
  EXPECT_EQ(odometry.estimator_type, kMavEstimatorTypeLidar);
}

TEST(MavlinkPoseEncoder, UnknownCovarianceIsNaN) {
  EXPECT_TRUE(std::isnan(vision_position_estimate(estimate_at(1, {0, 0, 0}, 1), 0).covariance[0]));
}

TEST(MavlinkPoseEncoder, ResetCounterStepsOnRestartsAndJumps) {
  ResetCounter counter(0.5, 5.0);
  EXPECT_EQ(counter.update(estimate_at(10.0, {0, 0, 1}, 100)), 0);
  EXPECT_EQ(counter.update(estimate_at(10.1, {0.4, 0, 1}, 101)), 0);  // 4 m/s: flying
  EXPECT_EQ(counter.update(estimate_at(10.2, {2.0, 0, 1}, 102)), 1);  // 1.6 m in 0.1 s: a jump
  EXPECT_EQ(counter.update(estimate_at(10.3, {2.0, 0, 1}, 3)), 2);    // matcher restarted
  EXPECT_EQ(counter.update(estimate_at(10.4, {2.1, 0, 1}, 4)), 2);
}

}  // namespace
}  // namespace uavslam::mavlink
