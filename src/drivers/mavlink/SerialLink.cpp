#include "drivers/mavlink/SerialLink.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>
#include <system_error>

namespace uavslam::mavlink {
namespace {

speed_t termios_speed(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 500000:
      return B500000;
    case 921600:
      return B921600;
    case 1000000:
      return B1000000;
    case 1500000:
      return B1500000;
    case 2000000:
      return B2000000;
    default:
      throw std::invalid_argument("unsupported baud rate " + std::to_string(baud));
  }
}

}  // namespace

SerialLink::SerialLink(const std::string& device, int baud)
    : description_("serial " + device + " at " + std::to_string(baud) + " baud") {
  const speed_t speed = termios_speed(baud);
  fd_ = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) throw std::system_error(errno, std::generic_category(), "cannot open " + device);
  termios tty{};
  if (::tcgetattr(fd_, &tty) != 0) {
    const int error = errno;
    ::close(fd_);
    throw std::system_error(error, std::generic_category(), device + " is not a serial port");
  }
  ::cfmakeraw(&tty);
  tty.c_cflag |= CLOCAL | CREAD;
  tty.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS | CSTOPB);
  ::cfsetispeed(&tty, speed);
  ::cfsetospeed(&tty, speed);
  if (::tcsetattr(fd_, TCSANOW, &tty) != 0) {
    const int error = errno;
    ::close(fd_);
    throw std::system_error(error, std::generic_category(), "cannot configure " + device);
  }
}

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
