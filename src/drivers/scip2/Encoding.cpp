#include "drivers/scip2/Encoding.hpp"

namespace uavslam::drivers::scip2 {
namespace {

constexpr unsigned char kOffset = 0x30;  // section 6: each 6-bit group is sent as value + 0x30
constexpr unsigned char kSixBits = 0x3F;

}  // namespace

std::optional<std::uint32_t> decode(std::string_view text) {
  if (text.empty() || text.size() > kFourCharacters) return std::nullopt;
  std::uint32_t value = 0;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < kOffset || byte > kOffset + kSixBits) return std::nullopt;
    value = (value << 6) | static_cast<std::uint32_t>(byte - kOffset);
  }
  return value;
}

std::string encode(std::uint32_t value, std::size_t width) {
  std::string text(width, '0');
  for (std::size_t i = width; i-- > 0;) {
    text[i] = static_cast<char>(kOffset + (value & kSixBits));
    value >>= 6;
  }
  return text;
}

char checksum(std::string_view line) {
  unsigned sum = 0;
  for (const char c : line) sum += static_cast<unsigned char>(c);
  return static_cast<char>((sum & kSixBits) + kOffset);  // section 7, "Sum"
}

bool has_valid_checksum(std::string_view line_with_sum) {
  if (line_with_sum.size() < 2) return false;
  return checksum(line_with_sum.substr(0, line_with_sum.size() - 1)) == line_with_sum.back();
}

}  // namespace uavslam::drivers::scip2
