#include "slam/TrackingMonitor.hpp"

#include <cmath>

namespace uavslam {

std::string to_string(Tracking state) {
  switch (state) {
    case Tracking::Tracking:
      return "tracking";
    case Tracking::Degraded:
      return "degraded";
    case Tracking::Lost:
      return "lost";
  }
  return "unknown";
}

std::string to_string(TrackingReason reason) {
  switch (reason) {
    case TrackingReason::None:
      return "";
    case TrackingReason::Degenerate:
      return "degenerate";
    case TrackingReason::Overload:
      return "overload";
    case TrackingReason::Gap:
      return "gap";
    case TrackingReason::Rejected:
      return "rejected";
    case TrackingReason::TooFewPoints:
      return "too_few_points";
    case TrackingReason::NoImu:
      return "no_imu";
    case TrackingReason::RepeatedRejections:
      return "repeated_rejections";
    case TrackingReason::PriorOverruled:
      return "prior_overruled";
  }
  return "unknown";
}

TrackingStatus TrackingMonitor::judge(const Scan& scan, const ScanReport& report,
                                      std::size_t skipped_before) {
  const TrackingStatus status =
      report.accepted() ? matched(report, skipped_before) : unmatched(scan, report);
  if (report.accepted()) last_matched_ = scan.stamp;
  if (std::isfinite(scan.stamp)) previous_scan_ = scan.stamp;
  return status;
}

// The most serious first: a pose found again after a gap or against the prior, a blind direction,
// then lateness.
TrackingStatus TrackingMonitor::matched(const ScanReport& report,
                                        std::size_t skipped_before) const {
  if (report.relocalised) return {Tracking::Degraded, TrackingReason::Gap};
  if (report.prior_overruled) return {Tracking::Degraded, TrackingReason::PriorOverruled};
  if (report.seen.degenerate > 0) return {Tracking::Degraded, TrackingReason::Degenerate};
  if (skipped_before > 0) return {Tracking::Degraded, TrackingReason::Overload};
  return {Tracking::Tracking, TrackingReason::None};
}

TrackingStatus TrackingMonitor::unmatched(const Scan& scan, const ScanReport& report) const {
  TrackingReason reason = TrackingReason::Rejected;
  if (report.outcome == ScanOutcome::TooFewPoints) reason = TrackingReason::TooFewPoints;
  if (report.outcome == ScanOutcome::NoImu) reason = TrackingReason::NoImu;
  const bool after_gap =
      previous_scan_ && stale_after_ > 0.0 && scan.stamp - *previous_scan_ > stale_after_;
  const bool stale = !last_matched_ || !std::isfinite(scan.stamp) ||
                     (stale_after_ > 0.0 && scan.stamp - *last_matched_ > stale_after_);
  if (!stale) return {Tracking::Degraded, reason};
  if (after_gap) return {Tracking::Lost, TrackingReason::Gap};
  if (reason == TrackingReason::Rejected) reason = TrackingReason::RepeatedRejections;
  return {Tracking::Lost, reason};
}

void TrackingCounts::add(const TrackingStatus& status) {
  ++states[static_cast<std::size_t>(status.state)];
  if (status.state != Tracking::Tracking) {
    ++reasons[to_string(status.state) + ": " + to_string(status.reason)];
  }
}

}  // namespace uavslam
