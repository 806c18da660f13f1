// The map's heading anchored on the orientation source's (beyond the seed; icp.heading:
// every_scan). The first scan founds the map at the heading of one sample of the source, off by
// that sample's noise n_0 (0.1-0.3 degrees of an autopilot's attitude), and with the heading
// estimated in every scan nothing turns the map back: 0.3 degrees is 0.15 m at 30 m from the
// take-off point. Each matched scan k measures the map's frame against the source's: its heading
// correction c_k = psi_map,k - psi_source,k = n_0 - n_k (the ICP's error smaller). Over the scans
// of the first `window` seconds the mean is n_0 to within the noise over the square root of
// their count:
//   turn = -(1/N) sum_k c_k
// and the map is turned once by it about the take-off point, onto the source's heading. The
// source's drift r over the window adds r window / 2 (2 degrees a minute over 3 s: 0.05 degree);
// a line through the corrections would take it out, but also takes a heading the first keyframes
// walked off for a drift, and anchored worse on every scenario measured (docs/algorithm.md).
#pragma once

#include <cstddef>
#include <optional>

namespace uavslam {

class HeadingAnchor {
 public:
  // window: seconds of scans averaged; 0: the map keeps the first sample's heading.
  explicit HeadingAnchor(double window) : window_(window) {}

  // A scan's heading correction (rad) once matched; the first call is the scan founding the map
  // (its correction 0 by construction), which only starts the clock. Returns the turn to give
  // the map, once: at the first scan `window` seconds or more after the founding one.
  std::optional<double> add(double stamp, double correction);

  // True once the map's heading is settled (at once without a window).
  bool settled() const { return window_ <= 0.0 || settled_; }

  // rad^2: how far the map's heading may be from the source's at the first scan. Until the turn,
  // one sample's noise (the corrections' variance s^2); once turned, their mean's, s^2 / N; 0
  // before two scans, or without a window (the first sample's heading is then the map's by
  // definition).
  double variance() const;

 private:
  double sample_variance() const;

  double window_;
  std::optional<double> start_;
  std::size_t n_ = 0;  // corrections so far, their sum and the sum of their squares
  double sum_ = 0.0;
  double squares_ = 0.0;
  bool settled_ = false;
};

}  // namespace uavslam
