#include "DelayLine.hpp"

#include <algorithm>
#include <stdexcept>

namespace uavslam::net {

DelayLine::DelayLine(const LinkImpairment& impairment)
    : impairment_(impairment), random_(impairment.seed) {
  if (impairment.loss < 0.0 || impairment.loss > 1.0) {
    throw std::invalid_argument("loss must be a share between 0 and 1");
  }
  if (impairment.delay.count() < 0 || impairment.jitter.count() < 0) {
    throw std::invalid_argument("delay and jitter must not be negative");
  }
}

bool DelayLine::admit(std::uint32_t id, Clock::time_point now) {
  ++counters_.packets;
  // Always draw both numbers so one packet's fate does not shift the sequence of the next.
  const bool lost = uniform_share() < impairment_.loss;
  const std::chrono::microseconds delay = jittered_delay();
  if (lost) {
    ++counters_.lost;
    return false;
  }
  last_due_ = std::max(last_due_, now + delay);
  held_.push_back({id, last_due_});
  counters_.max_held = std::max(counters_.max_held, held_.size());
  return true;
}

std::vector<std::uint32_t> DelayLine::release_due(Clock::time_point now) {
  std::vector<std::uint32_t> due;
  while (!held_.empty() && held_.front().due <= now) {
    due.push_back(held_.front().id);
    held_.pop_front();
  }
  return due;
}

std::vector<std::uint32_t> DelayLine::release_all() {
  std::vector<std::uint32_t> all;
  for (const HeldPacket& packet : held_) all.push_back(packet.id);
  held_.clear();
  return all;
}

std::optional<DelayLine::Clock::time_point> DelayLine::next_due() const {
  if (held_.empty()) return std::nullopt;
  return held_.front().due;
}

double DelayLine::uniform_share() {
  // The top 53 bits as a double in [0, 1): std::uniform_real_distribution is not the same on
  // every standard library, and a seed must reproduce the same losses.
  return static_cast<double>(random_() >> 11) * 0x1.0p-53;
}

std::chrono::microseconds DelayLine::jittered_delay() {
  const std::int64_t spread = impairment_.jitter.count();
  const std::int64_t offset =
      static_cast<std::int64_t>(random_() % static_cast<std::uint64_t>(2 * spread + 1)) - spread;
  return std::max(std::chrono::microseconds(0),
                  impairment_.delay + std::chrono::microseconds(offset));
}

}  // namespace uavslam::net
