// The MAVLink checksum: CRC-16/MCRF4XX (the "X.25" accumulator of the MAVLink spec: polynomial
// 0x1021 reflected, initial value 0xFFFF, no final XOR), over every frame byte after the start
// marker and then the message's CRC_EXTRA byte (mavlink.io/en/guide/serialization.html,
// "Checksum").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace uavslam::mavlink {

inline constexpr std::uint16_t kCrcInit = 0xFFFF;

// Folds one byte into a running checksum (the spec's crc_accumulate).
std::uint16_t crc_accumulate(std::uint8_t byte, std::uint16_t crc);
std::uint16_t crc_accumulate(const std::uint8_t* bytes, std::size_t count, std::uint16_t crc);
std::uint16_t crc_accumulate(const std::string& text, std::uint16_t crc);

}  // namespace uavslam::mavlink
