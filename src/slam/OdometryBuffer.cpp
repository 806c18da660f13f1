#include "slam/OdometryBuffer.hpp"

#include <algorithm>
#include <cmath>

namespace uavslam {

OdometryBuffer::OdometryBuffer(double max_gap, std::size_t capacity)
    : max_gap_(max_gap), capacity_(std::max<std::size_t>(capacity, 2)) {}

bool OdometryBuffer::add(const OdometrySample& sample) {
  if (!std::isfinite(sample.stamp) || !sample.position.allFinite() ||
      (!samples_.empty() && sample.stamp <= samples_.back().stamp)) {
    ++rejected_;
    return false;
  }
  samples_.push_back(sample);
  if (samples_.size() > capacity_) samples_.pop_front();
  return true;
}

std::optional<Vec3> OdometryBuffer::position_at(double t) const {
  if (samples_.empty() || !std::isfinite(t)) return std::nullopt;
  const auto after =
      std::lower_bound(samples_.begin(), samples_.end(), t,
                       [](const OdometrySample& s, double time) { return s.stamp < time; });
  if (after != samples_.end() && after->stamp == t) return after->position;
  if (after == samples_.end() || after == samples_.begin()) return std::nullopt;
  const OdometrySample& before = *std::prev(after);
  if (t - before.stamp > max_gap_ || after->stamp - t > max_gap_) return std::nullopt;
  const double s = (t - before.stamp) / (after->stamp - before.stamp);
  return before.position + s * (after->position - before.position);
}

}  // namespace uavslam
