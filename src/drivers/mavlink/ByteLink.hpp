// A byte pipe to the autopilot (UDP or serial), as the MAVLink session needs it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace uavslam::mavlink {

class ByteLink {
 public:
  virtual ~ByteLink() = default;
  // Up to `capacity` bytes into `buffer`, waiting at most timeout_ms; 0 on timeout. Throws
  // std::system_error when the link failed.
  virtual std::size_t receive(std::uint8_t* buffer, std::size_t capacity, int timeout_ms) = 0;
  // Sends the bytes; false when they could not go (no peer known yet, a full buffer).
  virtual bool send(const std::vector<std::uint8_t>& bytes) = 0;
  virtual std::string description() const = 0;
};

}  // namespace uavslam::mavlink
