#include "drivers/serial/SerialPort.hpp"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>
#include <system_error>

namespace uavslam::drivers {
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

[[noreturn]] void fail(int fd, const std::string& what) {
  const int error = errno;
  ::close(fd);
  throw std::system_error(error, std::generic_category(), what);
}

}  // namespace

int open_raw_serial(const std::string& device, int baud) {
  const speed_t speed = termios_speed(baud);
  const int fd = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw std::system_error(errno, std::generic_category(), "cannot open " + device);
  termios tty{};
  if (::tcgetattr(fd, &tty) != 0) fail(fd, device + " is not a serial port");
  ::cfmakeraw(&tty);
  tty.c_cflag |= CLOCAL | CREAD;
  tty.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS | CSTOPB);
  ::cfsetispeed(&tty, speed);
  ::cfsetospeed(&tty, speed);
  tty.c_cc[VMIN] = 0;
  tty.c_cc[VTIME] = 0;
  if (::tcsetattr(fd, TCSANOW, &tty) != 0) fail(fd, "cannot configure " + device);
  ::tcflush(fd, TCIOFLUSH);
  return fd;
}

}  // namespace uavslam::drivers
