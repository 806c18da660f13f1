// The tracking state the matcher reports with every scan: tracking, degraded or lost, and why.
#include <gtest/gtest.h>

#include "slam/TrackingMonitor.hpp"

namespace uavslam {
namespace {

Scan scan_at(double stamp) {
  Scan scan;
  scan.stamp = stamp;
  return scan;
}

ScanReport with(ScanOutcome outcome) {
  ScanReport report;
  report.outcome = outcome;
  return report;
}

class Monitor : public ::testing::Test {
 protected:
  TrackingMonitor monitor{0.5};  // recovery.gap: lost after 0.5 s without a match

  TrackingStatus judge(double stamp, const ScanReport& report, std::size_t skipped = 0) {
    return monitor.judge(scan_at(stamp), report, skipped);
  }
};

void expect(const TrackingStatus& status, Tracking state, TrackingReason reason) {
  EXPECT_EQ(to_string(status.state), to_string(state));
  EXPECT_EQ(to_string(status.reason), to_string(reason));
}

TEST_F(Monitor, AMatchThatSawEverythingIsTracking) {
  expect(judge(0.0, with(ScanOutcome::MapInitialised)), Tracking::Tracking, TrackingReason::None);
  expect(judge(0.025, with(ScanOutcome::Accepted)), Tracking::Tracking, TrackingReason::None);
}

TEST_F(Monitor, LostBeforeTheFirstMatch) {
  expect(judge(0.0, with(ScanOutcome::NoImu)), Tracking::Lost, TrackingReason::NoImu);
  expect(judge(0.1, with(ScanOutcome::TooFewPoints)), Tracking::Lost, TrackingReason::TooFewPoints);
}

TEST_F(Monitor, ABlindDirectionAGapOrLatenessDegradeAMatch) {
  judge(0.0, with(ScanOutcome::MapInitialised));
  ScanReport corridor = with(ScanOutcome::Accepted);
  corridor.seen.degenerate = 1;
  expect(judge(0.025, corridor), Tracking::Degraded, TrackingReason::Degenerate);
  expect(judge(0.05, with(ScanOutcome::Accepted), 3), Tracking::Degraded, TrackingReason::Overload);
  ScanReport found_again = with(ScanOutcome::Accepted);
  found_again.relocalised = true;
  expect(judge(2.0, found_again), Tracking::Degraded, TrackingReason::Gap);
  ScanReport against_the_prior = with(ScanOutcome::Accepted);
  against_the_prior.prior_overruled = true;
  against_the_prior.seen.degenerate = 1;
  expect(judge(2.025, against_the_prior), Tracking::Degraded, TrackingReason::PriorOverruled);
}

// Rejections degrade the state until no scan has matched for recovery.gap; then it is lost.
TEST_F(Monitor, RepeatedRejectionsLoseTheVehicle) {
  judge(0.0, with(ScanOutcome::MapInitialised));
  for (int i = 1; i <= 19; ++i) {  // to 0.475 s
    expect(judge(0.025 * i, with(ScanOutcome::ErrorTooLarge)), Tracking::Degraded,
           TrackingReason::Rejected);
  }
  expect(judge(0.525, with(ScanOutcome::DisagreesWithPrior)), Tracking::Lost,
         TrackingReason::RepeatedRejections);
  expect(judge(0.55, with(ScanOutcome::TooFewPoints)), Tracking::Lost,
         TrackingReason::TooFewPoints);
  expect(judge(0.575, with(ScanOutcome::Accepted)), Tracking::Tracking, TrackingReason::None);
}

TEST_F(Monitor, NoScansForLongerThanTheGapIsLostToTheGap) {
  judge(0.0, with(ScanOutcome::MapInitialised));
  expect(judge(2.0, with(ScanOutcome::NoCorrespondences)), Tracking::Lost, TrackingReason::Gap);
}

TEST(TrackingMonitor, WithoutAGapSettingOnlyTheStartIsLost) {
  TrackingMonitor monitor(0.0);
  EXPECT_EQ(monitor.judge(scan_at(0.0), with(ScanOutcome::NoImu), 0).state, Tracking::Lost);
  monitor.judge(scan_at(0.1), with(ScanOutcome::MapInitialised), 0);
  EXPECT_EQ(monitor.judge(scan_at(60.0), with(ScanOutcome::ErrorTooLarge), 0).state,
            Tracking::Degraded);
}

}  // namespace
}  // namespace uavslam
