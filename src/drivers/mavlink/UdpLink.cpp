#include "drivers/mavlink/UdpLink.hpp"

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace uavslam::mavlink {

UdpLink::UdpLink(const std::string& bind_address, int port)
    : description_("udp " + bind_address + ":" + std::to_string(port)) {
  sockaddr_in local{};
  local.sin_family = AF_INET;
  local.sin_port = htons(static_cast<std::uint16_t>(port));
  if (port <= 0 || port > 65535 || inet_pton(AF_INET, bind_address.c_str(), &local.sin_addr) != 1) {
    throw std::system_error(EINVAL, std::generic_category(), "bad UDP address " + description_);
  }
  socket_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (socket_ < 0) throw std::system_error(errno, std::generic_category(), "socket");
  if (::bind(socket_, reinterpret_cast<const sockaddr*>(&local), sizeof(local)) != 0) {
    const int error = errno;
    ::close(socket_);
    throw std::system_error(error, std::generic_category(), "cannot bind " + description_);
  }
}

UdpLink::~UdpLink() {
  if (socket_ >= 0) ::close(socket_);
}

std::size_t UdpLink::receive(std::uint8_t* buffer, std::size_t capacity, int timeout_ms) {
  pollfd ready{socket_, POLLIN, 0};
  const int polled = ::poll(&ready, 1, timeout_ms);
  if (polled < 0 && errno != EINTR) throw std::system_error(errno, std::generic_category(), "poll");
  if (polled <= 0) return 0;
  sockaddr_in source{};
  socklen_t source_size = sizeof(source);
  const ssize_t got =
      ::recvfrom(socket_, buffer, capacity, 0, reinterpret_cast<sockaddr*>(&source), &source_size);
  if (got < 0) {
    if (errno == EINTR || errno == EAGAIN) return 0;
    throw std::system_error(errno, std::generic_category(), "recvfrom " + description_);
  }
  peer_ = source;
  has_peer_ = true;
  return static_cast<std::size_t>(got);
}

bool UdpLink::send(const std::vector<std::uint8_t>& bytes) {
  if (!has_peer_) return false;
  return ::sendto(socket_, bytes.data(), bytes.size(), MSG_DONTWAIT,
                  reinterpret_cast<const sockaddr*>(&peer_),
                  sizeof(peer_)) == static_cast<ssize_t>(bytes.size());
}

}  // namespace uavslam::mavlink
