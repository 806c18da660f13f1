// MAVLink over UDP as companion links use it (PX4's and ArduPilot's ports 14540/14550): we bind a
// port (on 127.0.0.1 unless told another address) and answer whichever address the autopilot's
// datagrams come from.
#pragma once

#include <netinet/in.h>

#include <string>

#include "drivers/mavlink/ByteLink.hpp"

namespace uavslam::mavlink {

class UdpLink : public ByteLink {
 public:
  // Throws std::system_error naming the address when the socket cannot be bound.
  UdpLink(const std::string& bind_address, int port);
  ~UdpLink() override;
  UdpLink(const UdpLink&) = delete;
  UdpLink& operator=(const UdpLink&) = delete;

  std::size_t receive(std::uint8_t* buffer, std::size_t capacity, int timeout_ms) override;
  bool send(const std::vector<std::uint8_t>& bytes) override;
  std::string description() const override { return description_; }

 private:
  int socket_ = -1;
  sockaddr_in peer_{};
  bool has_peer_ = false;
  std::string description_;
};

}  // namespace uavslam::mavlink
