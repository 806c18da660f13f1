#include "drivers/scip2/ByteLink.hpp"

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "drivers/serial/SerialPort.hpp"

namespace uavslam::drivers::scip2 {
namespace {

bool wait_writable(int fd, int timeout_ms) {
  pollfd p{fd, POLLOUT, 0};
  return ::poll(&p, 1, timeout_ms) == 1 && (p.revents & POLLOUT);
}

}  // namespace

ByteLink::~ByteLink() {
  ::close(fd_);
}

ByteLink::Read ByteLink::read(std::string& out, int timeout_ms) {
  pollfd p{fd_, POLLIN, 0};
  const int ready = ::poll(&p, 1, timeout_ms);
  if (ready < 0) return errno == EINTR ? Read::Timeout : Read::Closed;
  if (ready == 0) return Read::Timeout;
  char buffer[4096];
  const ssize_t n = ::read(fd_, buffer, sizeof buffer);
  if (n > 0) {
    out.append(buffer, static_cast<std::size_t>(n));
    return Read::Data;
  }
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return Read::Timeout;
  return Read::Closed;  // EOF (peer closed, pty master gone) or EIO/ENODEV (unplugged)
}

bool ByteLink::write(std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
      if (!wait_writable(fd_, 1000)) return false;
      continue;
    }
    if (n <= 0) return false;
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// SCIP 2.0 over USB ignores the line rate; 115200 suits the RS-232 models' default.
std::unique_ptr<ByteLink> open_serial(const std::string& path, std::string& error) {
  try {
    return std::make_unique<ByteLink>(open_raw_serial(path, 115200));
  } catch (const std::system_error& e) {
    error = e.what();
    return nullptr;
  }
}

std::unique_ptr<ByteLink> open_tcp(const std::string& host, int port, int timeout_ms,
                                   std::string& error) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const std::string service = std::to_string(port);
  if (const int code = ::getaddrinfo(host.c_str(), service.c_str(), &hints, &found); code != 0) {
    error = "cannot resolve " + host + ": " + ::gai_strerror(code);
    return nullptr;
  }
  error = "no address for " + host;
  for (addrinfo* a = found; a; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) continue;
    const int connected = ::connect(fd, a->ai_addr, a->ai_addrlen);
    int problem = 0;
    socklen_t length = sizeof problem;
    if ((connected == 0 || (errno == EINPROGRESS && wait_writable(fd, timeout_ms))) &&
        ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &problem, &length) == 0 && problem == 0) {
      ::freeaddrinfo(found);
      return std::make_unique<ByteLink>(fd);
    }
    error = "cannot connect to " + host + ":" + service + ": " +
            std::strerror(problem ? problem : ETIMEDOUT);
    ::close(fd);
  }
  ::freeaddrinfo(found);
  return nullptr;
}

}  // namespace uavslam::drivers::scip2
