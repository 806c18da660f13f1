// One MAVLink frame, v1 or v2 (mavlink.io/en/guide/serialization.html, "Packet Format"):
// v1: 0xFE len seq sysid compid msgid(1) payload crc(2)
// v2: 0xFD len incompat compat seq sysid compid msgid(3, little-endian) payload crc(2)
//     [signature(13) when incompat_flags has MAVLINK_IFLAG_SIGNED (0x01)]
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace uavslam::mavlink {

inline constexpr std::uint8_t kStxV1 = 0xFE;
inline constexpr std::uint8_t kStxV2 = 0xFD;
inline constexpr std::size_t kHeaderV1 = 6;  // bytes from the marker up to the payload
inline constexpr std::size_t kHeaderV2 = 10;
inline constexpr std::size_t kChecksumBytes = 2;
inline constexpr std::uint8_t kIncompatSigned = 0x01;  // MAVLINK_IFLAG_SIGNED
inline constexpr std::size_t kSignatureBytes = 13;     // link id, 48-bit timestamp, 48-bit hash

struct Frame {
  int version = 2;  // 1 or 2
  std::uint8_t incompat_flags = 0;
  std::uint8_t compat_flags = 0;
  std::uint8_t sequence = 0;
  std::uint8_t system_id = 0;
  std::uint8_t component_id = 0;
  std::uint32_t message_id = 0;
  // As received: a v2 sender drops trailing zero bytes, so it may be shorter than the message;
  // PayloadReader reads the missing bytes as zeros.
  std::vector<std::uint8_t> payload;
  bool is_signed() const { return (incompat_flags & kIncompatSigned) != 0; }
};

// The MAVLink 2 signature block (mavlink.io/en/guide/message_signing.html): carried, never
// checked here.
struct Signature {
  std::uint8_t link_id = 0;
  std::uint64_t timestamp = 0;  // 10 us units since 2015-01-01, 48 bits on the wire
  std::array<std::uint8_t, 6> hash{};
};

}  // namespace uavslam::mavlink
