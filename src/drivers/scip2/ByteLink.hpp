// A byte stream to a sensor: a serial port (USB CDC-ACM or RS-232, raw mode) or a TCP connection
// (Ethernet models), read with a timeout. What goes away (unplugged: EIO/ENODEV; peer closed:
// EOF) reads as Closed, for the owner to reconnect.
#pragma once

#include <memory>
#include <string>
#include <string_view>

namespace uavslam::drivers::scip2 {

class ByteLink {
 public:
  enum class Read { Data, Timeout, Closed };

  explicit ByteLink(int fd) : fd_(fd) {}
  ~ByteLink();
  ByteLink(const ByteLink&) = delete;
  ByteLink& operator=(const ByteLink&) = delete;

  // Appends what arrives within `timeout_ms` (at most 4 KB) to `out`.
  Read read(std::string& out, int timeout_ms);
  // Writes all of `bytes`; false when the link went away.
  bool write(std::string_view bytes);

 private:
  int fd_;
};

// A tty (e.g. /dev/ttyACM0, or a pseudo-terminal) in raw mode, 8N1; USB models ignore the rate.
// nullptr with `error` set when it cannot be opened.
std::unique_ptr<ByteLink> open_serial(const std::string& path, std::string& error);
// A TCP connection to host:port (numeric address or name), within `timeout_ms`.
std::unique_ptr<ByteLink> open_tcp(const std::string& host, int port, int timeout_ms,
                                   std::string& error);

}  // namespace uavslam::drivers::scip2
