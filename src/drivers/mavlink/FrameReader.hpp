// Splits a byte stream (UDP datagrams or serial reads, in any chunking) into MAVLink v1 and v2
// frames. A frame is handed on only when its checksum, seeded with its message's CRC_EXTRA,
// matches. Bytes before a start marker are garbage; a bad checksum skips just the marker byte, so
// a real frame hiding inside a corrupted one is still found; a frame of a message this driver
// does not know cannot be checked and is skipped whole when a marker (or the end of the input)
// follows it, else its marker is taken for garbage. Sequence numbers are followed per
// (system, component) to count lost frames. Signed v2 frames are accepted (the signature is
// carried past, not verified). Holds at most one partial frame between calls.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

#include "drivers/mavlink/Frame.hpp"

namespace uavslam::mavlink {

struct FrameCounts {
  std::uint64_t frames = 0;            // checked and handed on
  std::uint64_t v1_frames = 0;         // of which MAVLink 1
  std::uint64_t signed_frames = 0;     // of which signed
  std::uint64_t crc_errors = 0;        // a marker whose frame failed its checksum
  std::uint64_t unknown_messages = 0;  // frames of messages not in CommonMessages (skipped)
  std::uint64_t unsupported_flags =
      0;                            // incompat_flags other than signing (dropped, as the spec says)
  std::uint64_t garbage_bytes = 0;  // bytes outside any frame
  std::uint64_t sequence_gaps = 0;  // frames missing from the senders' sequence numbers
};

class FrameReader {
 public:
  using OnFrame = std::function<void(const Frame&)>;

  // Parses `size` bytes following the ones fed before; on_frame runs for each good frame.
  void feed(const std::uint8_t* data, std::size_t size, const OnFrame& on_frame);
  const FrameCounts& counts() const { return counts_; }

 private:
  // What the bytes at buffer_[pos] hold.
  enum class Step { kNeedMore, kSkipByte, kSkipFrame, kFrame };
  Step examine(std::size_t pos, std::size_t& frame_size, Frame& frame);
  void count_sequence(const Frame& frame);

  std::vector<std::uint8_t> buffer_;
  std::map<std::uint16_t, std::uint8_t> last_sequence_;  // (sysid << 8 | compid) -> seq
  FrameCounts counts_;
};

}  // namespace uavslam::mavlink
