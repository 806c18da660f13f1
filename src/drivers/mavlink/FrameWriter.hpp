// Builds MAVLink frames from payloads, numbering them with this sender's sequence counter.
// MAVLink 2 drops the payload's trailing zero bytes (keeping at least one; serialization.html,
// "Payload Truncation"); MAVLink 1 sends the base fields only (extensions are MAVLink 2 only).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "drivers/mavlink/CommonMessages.hpp"
#include "drivers/mavlink/Frame.hpp"

namespace uavslam::mavlink {

class FrameWriter {
 public:
  FrameWriter(std::uint8_t system_id, std::uint8_t component_id, int version = 2)
      : system_id_(system_id), component_id_(component_id), version_(version) {}

  // The frame of message `id` with `payload` (its full length, as the codecs make it). A
  // signature, if given, is appended with the signed flag (its hash is not computed here).
  std::vector<std::uint8_t> frame(MessageId id, const std::vector<std::uint8_t>& payload,
                                  const std::optional<Signature>& signature = std::nullopt);

  std::uint8_t next_sequence() const { return sequence_; }
  // A companion computer takes its vehicle's system id once it has heard the autopilot.
  void set_system_id(std::uint8_t system_id) { system_id_ = system_id; }
  // Skips sequence numbers, as a lossy link would (the emulator's fault injection).
  void skip_sequence(std::uint8_t count) {
    sequence_ = static_cast<std::uint8_t>(sequence_ + count);
  }

 private:
  std::uint8_t system_id_;
  std::uint8_t component_id_;
  int version_;
  std::uint8_t sequence_ = 0;
};

}  // namespace uavslam::mavlink
