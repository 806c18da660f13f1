// How well the vehicle is tracked, scan by scan, for those who fly on the pose (the autopilot, the
// ground station): an honest state with its reason, beside the covariance.
//   tracking  the scan matched and fixed every direction;
//   degraded  a pose was given, but part of it is the motion prior's: a direction the scan cannot
//             see (degenerate), a rejected scan carried by the prior (rejected, too_few_points,
//             no_imu), the match found again after a gap (gap), a match taken against a
//             prior that the gate had found drifted (prior_overruled: the pose jumped), or scans
//             dropped unprocessed because the matcher fell behind (overload);
//   lost      no scan has matched for longer than recovery.gap (the time after which the last
//             position is stale): the reason is why the latest failed (gap: no scans came;
//             too_few_points, no_imu; repeated_rejections for any other).
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <string>

#include "core/SlamPipeline.hpp"

namespace uavslam {

enum class Tracking { Tracking, Degraded, Lost };

enum class TrackingReason {
  None,
  Degenerate,
  Overload,
  Gap,
  Rejected,
  TooFewPoints,
  NoImu,
  RepeatedRejections,
  PriorOverruled,
};

struct TrackingStatus {
  Tracking state = Tracking::Lost;
  TrackingReason reason = TrackingReason::None;
};

std::string to_string(Tracking state);
std::string to_string(TrackingReason reason);

// A run's tally: scans per state, and per "state: reason" for those not tracking.
struct TrackingCounts {
  std::array<std::size_t, 3> states{};  // by Tracking
  std::map<std::string, std::size_t> reasons;

  void add(const TrackingStatus& status);
};

class TrackingMonitor {
 public:
  // stale_after: s without a matched scan after which the vehicle is lost (recovery.gap; 0: only
  // before the first match).
  explicit TrackingMonitor(double stale_after) : stale_after_(stale_after) {}

  // skipped_before: scans the caller dropped unprocessed just before this one (it fell behind).
  TrackingStatus judge(const Scan& scan, const ScanReport& report, std::size_t skipped_before);

 private:
  TrackingStatus matched(const ScanReport& report, std::size_t skipped_before) const;
  TrackingStatus unmatched(const Scan& scan, const ScanReport& report) const;

  double stale_after_;
  std::optional<double> last_matched_;
  std::optional<double> previous_scan_;
};

}  // namespace uavslam
