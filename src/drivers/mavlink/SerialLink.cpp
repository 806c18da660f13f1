#include "drivers/mavlink/SerialLink.hpp"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>
#include <system_error>

#include "drivers/serial/SerialPort.hpp"

namespace uavslam::mavlink {

SerialLink::SerialLink(const std::string& device, int baud)
    : fd_(drivers::open_raw_serial(device, baud)),
      description_("serial " + device + " at " + std::to_string(baud) + " baud") {}

SerialLink::~SerialLink() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t SerialLink::receive(std::uint8_t* buffer, std::size_t capacity, int timeout_ms) {
  pollfd ready{fd_, POLLIN, 0};
  const int polled = ::poll(&ready, 1, timeout_ms);
  if (polled < 0 && errno != EINTR) throw std::system_error(errno, std::generic_category(), "poll");
  if (polled <= 0) return 0;
  const ssize_t got = ::read(fd_, buffer, capacity);
  if (got < 0) {
    if (errno == EINTR || errno == EAGAIN) return 0;
    throw std::system_error(errno, std::generic_category(), "read " + description_);
  }
  if (got == 0) throw std::system_error(ENODEV, std::generic_category(), description_ + " closed");
  return static_cast<std::size_t>(got);
}

bool SerialLink::send(const std::vector<std::uint8_t>& bytes) {
  return ::write(fd_, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
}

}  // namespace uavslam::mavlink
