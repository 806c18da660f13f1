#include "drivers/mavlink/Crc.hpp"

namespace uavslam::mavlink {

// The byte-wise form of the reflected CCITT polynomial given in the MAVLink spec's checksum.h.
std::uint16_t crc_accumulate(std::uint8_t byte, std::uint16_t crc) {
  std::uint8_t tmp = static_cast<std::uint8_t>(byte ^ static_cast<std::uint8_t>(crc & 0xFF));
  tmp = static_cast<std::uint8_t>(tmp ^ static_cast<std::uint8_t>(tmp << 4));
  return static_cast<std::uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
}

std::uint16_t crc_accumulate(const std::uint8_t* bytes, std::size_t count, std::uint16_t crc) {
  for (std::size_t i = 0; i < count; ++i) crc = crc_accumulate(bytes[i], crc);
  return crc;
}

std::uint16_t crc_accumulate(const std::string& text, std::uint16_t crc) {
  for (const char c : text) crc = crc_accumulate(static_cast<std::uint8_t>(c), crc);
  return crc;
}

}  // namespace uavslam::mavlink
