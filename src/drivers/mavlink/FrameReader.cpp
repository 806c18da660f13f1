#include "drivers/mavlink/FrameReader.hpp"

#include "drivers/mavlink/CommonMessages.hpp"
#include "drivers/mavlink/Crc.hpp"

namespace uavslam::mavlink {

void FrameReader::feed(const std::uint8_t* data, std::size_t size, const OnFrame& on_frame) {
  buffer_.insert(buffer_.end(), data, data + size);
  std::size_t pos = 0;
  Frame frame;
  while (pos < buffer_.size()) {
    if (buffer_[pos] != kStxV1 && buffer_[pos] != kStxV2) {
      ++counts_.garbage_bytes;
      ++pos;
      continue;
    }
    std::size_t frame_size = 0;
    const Step step = examine(pos, frame_size, frame);
    if (step == Step::kNeedMore) break;
    if (step == Step::kSkipByte) {
      ++pos;
      continue;
    }
    pos += frame_size;
    if (step == Step::kFrame) {
      count_sequence(frame);
      ++counts_.frames;
      if (frame.version == 1) ++counts_.v1_frames;
      if (frame.is_signed()) ++counts_.signed_frames;
      on_frame(frame);
    }
  }
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(pos));
}

FrameReader::Step FrameReader::examine(std::size_t pos, std::size_t& frame_size, Frame& frame) {
  const std::size_t available = buffer_.size() - pos;
  const std::uint8_t* bytes = buffer_.data() + pos;
  const bool v2 = bytes[0] == kStxV2;
  const std::size_t header = v2 ? kHeaderV2 : kHeaderV1;
  if (available < header) return Step::kNeedMore;
  const std::size_t length = bytes[1];
  frame.version = v2 ? 2 : 1;
  frame.incompat_flags = v2 ? bytes[2] : 0;
  frame.compat_flags = v2 ? bytes[3] : 0;
  frame.sequence = bytes[v2 ? 4 : 2];
  frame.system_id = bytes[v2 ? 5 : 3];
  frame.component_id = bytes[v2 ? 6 : 4];
  frame.message_id = v2 ? static_cast<std::uint32_t>(bytes[7]) |
                              static_cast<std::uint32_t>(bytes[8]) << 8 |
                              static_cast<std::uint32_t>(bytes[9]) << 16
                        : bytes[5];
  const std::size_t signature = frame.is_signed() ? kSignatureBytes : 0;
  frame_size = header + length + kChecksumBytes + signature;
  if (available < frame_size) return Step::kNeedMore;

  const MessageDefinition* definition = find_definition(frame.message_id);
  if (!definition) {
    // It cannot be checked: take it for a frame only when its flags are ones senders set and
    // another frame (or the end of the bytes) follows it, else it is a false marker in garbage,
    // and skipping its length could swallow good frames.
    const std::size_t next = pos + frame_size;
    const bool followed =
        next == buffer_.size() || buffer_[next] == kStxV1 || buffer_[next] == kStxV2;
    if ((frame.incompat_flags & ~kIncompatSigned) != 0 || !followed) return Step::kSkipByte;
    ++counts_.unknown_messages;
    return Step::kSkipFrame;
  }
  std::uint16_t crc = crc_accumulate(bytes + 1, header - 1 + length, kCrcInit);
  crc = crc_accumulate(definition->crc_extra(), crc);
  const std::uint8_t* checksum = bytes + header + length;
  const auto received = static_cast<std::uint16_t>(checksum[0] | checksum[1] << 8);
  if (crc != received) {
    ++counts_.crc_errors;
    return Step::kSkipByte;
  }
  if ((frame.incompat_flags & ~kIncompatSigned) != 0) {
    ++counts_.unsupported_flags;
    return Step::kSkipFrame;
  }
  frame.payload.assign(bytes + header, bytes + header + length);
  return Step::kFrame;
}

void FrameReader::count_sequence(const Frame& frame) {
  const auto sender = static_cast<std::uint16_t>(frame.system_id << 8 | frame.component_id);
  const auto last = last_sequence_.find(sender);
  if (last != last_sequence_.end()) {
    counts_.sequence_gaps += static_cast<std::uint8_t>(frame.sequence - last->second - 1);
  }
  last_sequence_[sender] = frame.sequence;
}

}  // namespace uavslam::mavlink
