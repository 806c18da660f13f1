// MAVLink over a serial port (an autopilot's TELEM port through a USB-UART): raw 8N1, no flow
// control, at the given baud rate.
#pragma once

#include <string>

#include "drivers/mavlink/ByteLink.hpp"

namespace uavslam::mavlink {

class SerialLink : public ByteLink {
 public:
  // Throws std::system_error naming the device (missing, no permission: see docs/devices.md's
  // dialout note) or std::invalid_argument for a baud rate termios does not have.
  SerialLink(const std::string& device, int baud);
  ~SerialLink() override;
  SerialLink(const SerialLink&) = delete;
  SerialLink& operator=(const SerialLink&) = delete;

  std::size_t receive(std::uint8_t* buffer, std::size_t capacity, int timeout_ms) override;
  bool send(const std::vector<std::uint8_t>& bytes) override;
  std::string description() const override { return description_; }

 private:
  int fd_ = -1;
  std::string description_;
};

}  // namespace uavslam::mavlink
