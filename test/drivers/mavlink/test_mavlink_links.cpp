// The serial link on a pseudo-terminal (raw bytes both ways at the requested baud rate) and the
// UDP link on 127.0.0.1 (answers go to whoever sent last); clear errors for bad devices.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <unistd.h>

#include <stdexcept>
#include <system_error>
#include <vector>

#include <gtest/gtest.h>

#include "drivers/mavlink/SerialLink.hpp"
#include "drivers/mavlink/UdpLink.hpp"

namespace uavslam::mavlink {
namespace {

using Bytes = std::vector<std::uint8_t>;

class PseudoTerminal {
 public:
  PseudoTerminal() : master_(posix_openpt(O_RDWR | O_NOCTTY)) {
    if (master_ >= 0 && (grantpt(master_) != 0 || unlockpt(master_) != 0)) {
      ::close(master_);
      master_ = -1;
    }
  }
  ~PseudoTerminal() {
    if (master_ >= 0) ::close(master_);
  }
  bool open() const { return master_ >= 0; }
  std::string device() const { return ptsname(master_); }
  int master() const { return master_; }

 private:
  int master_;
};

Bytes receive_all(ByteLink& link, std::size_t count) {
  Bytes got;
  std::uint8_t buffer[256];
  for (int tries = 0; got.size() < count && tries < 100; ++tries) {
    const std::size_t n = link.receive(buffer, sizeof(buffer), 100);
    got.insert(got.end(), buffer, buffer + n);
  }
  return got;
}

TEST(MavlinkSerialLink, CarriesRawBytesBothWays) {
  PseudoTerminal pty;
  ASSERT_TRUE(pty.open());
  SerialLink link(pty.device(), 921600);
  const Bytes frame = {0xFD, 0x09, 0x00, 0x11, 0x13, 0x0A, 0x0D, 0xFF, 0x00};  // CR, LF, XON
  ASSERT_EQ(::write(pty.master(), frame.data(), frame.size()), static_cast<ssize_t>(frame.size()));
  EXPECT_EQ(receive_all(link, frame.size()), frame);  // no line discipline in between
  ASSERT_TRUE(link.send(frame));
  Bytes back(frame.size());
  std::size_t got = 0;
  for (int tries = 0; got < back.size() && tries < 100; ++tries) {
    pollfd ready{pty.master(), POLLIN, 0};
    if (::poll(&ready, 1, 100) <= 0) continue;
    const ssize_t n = ::read(pty.master(), back.data() + got, back.size() - got);
    if (n > 0) got += static_cast<std::size_t>(n);
  }
  EXPECT_EQ(back, frame);
}

TEST(MavlinkSerialLink, RefusesMissingDevicesAndUnknownBaudRates) {
  EXPECT_THROW(SerialLink("/nonexistent/ttyUSB9", 921600), std::system_error);
  EXPECT_THROW(SerialLink("/dev/null", 12345), std::invalid_argument);
  EXPECT_THROW(SerialLink("/dev/null", 57600), std::system_error);  // not a terminal
}

TEST(MavlinkUdpLink, AnswersTheLastSender) {
  constexpr int kPort = 24560;
  UdpLink link("127.0.0.1", kPort);
  EXPECT_FALSE(link.send({1, 2, 3}));  // nobody to answer yet
  const int peer = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(peer, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(kPort);
  inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
  const Bytes hello = {0xFE, 0x00, 0x01};
  ASSERT_EQ(
      ::sendto(peer, hello.data(), hello.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof(to)),
      3);
  EXPECT_EQ(receive_all(link, hello.size()), hello);
  ASSERT_TRUE(link.send({7, 8}));
  pollfd ready{peer, POLLIN, 0};
  ASSERT_EQ(::poll(&ready, 1, 5000), 1);
  std::uint8_t answer[8];
  EXPECT_EQ(::recv(peer, answer, sizeof(answer), 0), 2);
  EXPECT_EQ(answer[0], 7);
  ::close(peer);
  EXPECT_THROW(UdpLink("127.0.0.1", kPort), std::system_error);  // the port is taken
  EXPECT_THROW(UdpLink("not-an-address", kPort + 1), std::system_error);
}

}  // namespace
}  // namespace uavslam::mavlink
