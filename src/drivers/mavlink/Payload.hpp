// Little-endian field access in a message payload (MAVLink serialises every multi-byte field
// little-endian). Reads past the received bytes give zeros, which is exactly how a MAVLink 2
// receiver restores a payload whose trailing zeros the sender truncated; nothing reads or writes
// past the buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

namespace uavslam::mavlink {
namespace detail {

template <std::size_t Bytes>
struct UnsignedOf;
template <>
struct UnsignedOf<1> {
  using type = std::uint8_t;
};
template <>
struct UnsignedOf<2> {
  using type = std::uint16_t;
};
template <>
struct UnsignedOf<4> {
  using type = std::uint32_t;
};
template <>
struct UnsignedOf<8> {
  using type = std::uint64_t;
};

}  // namespace detail

class PayloadReader {
 public:
  explicit PayloadReader(const std::vector<std::uint8_t>& bytes) : bytes_(bytes) {}

  template <typename T>
  T get(std::size_t offset) const {
    static_assert(std::is_arithmetic_v<T>);
    using Bits = typename detail::UnsignedOf<sizeof(T)>::type;
    Bits bits = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      const std::uint8_t byte = offset + i < bytes_.size() ? bytes_[offset + i] : 0;
      bits = static_cast<Bits>(bits | static_cast<Bits>(static_cast<Bits>(byte) << (8 * i)));
    }
    T value;
    std::memcpy(&value, &bits, sizeof(T));
    return value;
  }

 private:
  const std::vector<std::uint8_t>& bytes_;
};

class PayloadWriter {
 public:
  explicit PayloadWriter(std::size_t length) : bytes_(length, 0) {}

  template <typename T>
  void put(std::size_t offset, T value) {
    static_assert(std::is_arithmetic_v<T>);
    using Bits = typename detail::UnsignedOf<sizeof(T)>::type;
    Bits bits;
    std::memcpy(&bits, &value, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T) && offset + i < bytes_.size(); ++i) {
      bytes_[offset + i] = static_cast<std::uint8_t>(bits >> (8 * i));
    }
  }

  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

}  // namespace uavslam::mavlink
