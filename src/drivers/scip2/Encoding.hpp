// SCIP 2.0 character encoding and line checksum (Hokuyo "Communication Protocol Specification For
// SCIP2.0 Standard", C-42-03320B). Every value on the wire is printable: 6 bits per character,
// offset by 0x30 (section 6, "Data Encoding and Decoding": 2-, 3- and 4-character encodings), and
// every line of a reply after the echo ends with one checksum character (section 7,
// "Communication Format": the low 6 bits of the sum of the line's bytes, plus 0x30).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace uavslam::drivers::scip2 {

// The encodings the specification defines: 2 characters (12 bits: MS/GS distances), 3 (18 bits:
// MD/GD distances, ME intensities) and 4 (24 bits: time stamps).
constexpr std::size_t kTwoCharacters = 2;
constexpr std::size_t kThreeCharacters = 3;
constexpr std::size_t kFourCharacters = 4;

// The value of `text` (its characters most significant first), or nullopt when a character lies
// outside 0x30..0x6F (not an encoded 6-bit value) or `text` is longer than 4 characters.
std::optional<std::uint32_t> decode(std::string_view text);

// `value` in `width` characters (the high bits beyond 6 * width are dropped).
std::string encode(std::uint32_t value, std::size_t width);

// The checksum character of `line` (the line's bytes without the checksum and the LF).
char checksum(std::string_view line);

// True when the last character of `line_with_sum` is the checksum of the rest.
bool has_valid_checksum(std::string_view line_with_sum);

}  // namespace uavslam::drivers::scip2
