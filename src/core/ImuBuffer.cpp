#include "core/ImuBuffer.hpp"

#include <algorithm>
#include <cmath>

namespace uavslam {

ImuBuffer::ImuBuffer(double max_gap, double history) : max_gap_(max_gap), history_(history) {}

void ImuBuffer::add(const ImuSample& sample) {
  if (!std::isfinite(sample.stamp) || !sample.orientation.coeffs().allFinite() ||
      sample.orientation.norm() < 1e-6 ||
      (!samples_.empty() && sample.stamp <= samples_.back().stamp)) {
    ++rejected_;
    return;
  }
  samples_.push_back(sample);
  samples_.back().orientation.normalize();
  while (samples_.front().stamp < sample.stamp - history_) samples_.pop_front();
}

std::optional<ImuBuffer::Around> ImuBuffer::around(double t) const {
  if (samples_.empty() || !std::isfinite(t)) return std::nullopt;
  const auto after =
      std::lower_bound(samples_.begin(), samples_.end(), t,
                       [](const ImuSample& s, double time) { return s.stamp < time; });
  const bool has_after = after != samples_.end();
  const bool has_before = after != samples_.begin();
  if (has_before && has_after && after->stamp - std::prev(after)->stamp <= 2.0 * max_gap_) {
    const ImuSample& before = *std::prev(after);
    return Around{&before, &*after, (t - before.stamp) / (after->stamp - before.stamp)};
  }
  // No pair close around t: the nearest single sample, if it is close enough.
  if (has_after && after->stamp - t <= max_gap_) return Around{&*after, &*after, 0.0};
  if (has_before && t - std::prev(after)->stamp <= max_gap_) {
    return Around{&*std::prev(after), &*std::prev(after), 0.0};
  }
  return std::nullopt;
}

std::optional<Eigen::Quaterniond> ImuBuffer::orientation_at(double t) const {
  const std::optional<Around> a = around(t);
  if (!a) return std::nullopt;
  if (a->first == a->second) return a->first->orientation;
  return a->first->orientation.slerp(a->fraction, a->second->orientation);
}

std::optional<Vec3> ImuBuffer::angular_velocity_at(double t) const {
  const std::optional<Around> a = around(t);
  if (!a) return std::nullopt;
  return (1.0 - a->fraction) * a->first->angular_velocity +
         a->fraction * a->second->angular_velocity;
}

}  // namespace uavslam
