// The decision part of the link emulator, apart from netfilter so it can be tested without root:
// every packet that enters is either lost (a seeded random share) or held until its release time
// (now + delay +- jitter). Release times never go backwards, so packets leave in the order they
// came, as on a real radio link where jitter comes from retransmissions and not from reordering.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <vector>

namespace uavslam::net {

struct LinkImpairment {
  std::chrono::microseconds delay{0};
  std::chrono::microseconds jitter{0};  // release time spread uniformly in [delay - j, delay + j]
  double loss = 0.0;                    // share of packets lost, 0..1
  std::uint64_t seed = 1;               // the same seed gives the same losses and jitter
};

struct DelayLineCounters {
  std::uint64_t packets = 0;  // every packet admitted, lost ones included
  std::uint64_t lost = 0;
  std::size_t max_held = 0;  // the most packets held at one time
};

class DelayLine {
 public:
  using Clock = std::chrono::steady_clock;

  explicit DelayLine(const LinkImpairment& impairment);

  // A packet `id` arrives at `now`: false if it is lost (the caller drops it at once), true if it
  // is now held until release_due hands it back.
  bool admit(std::uint32_t id, Clock::time_point now);

  // The held packets whose release time has come by `now`, in arrival order.
  std::vector<std::uint32_t> release_due(Clock::time_point now);

  // Everything still held, in arrival order (for a clean stop); the line is empty afterwards.
  std::vector<std::uint32_t> release_all();

  // When the next held packet is due; nothing if none is held.
  std::optional<Clock::time_point> next_due() const;

  std::size_t held() const { return held_.size(); }
  const DelayLineCounters& counters() const { return counters_; }

 private:
  struct HeldPacket {
    std::uint32_t id;
    Clock::time_point due;
  };

  double uniform_share();  // in [0, 1), the same sequence for the same seed on every platform
  std::chrono::microseconds jittered_delay();

  LinkImpairment impairment_;
  std::mt19937_64 random_;
  std::deque<HeldPacket> held_;
  Clock::time_point last_due_{};
  DelayLineCounters counters_;
};

}  // namespace uavslam::net
