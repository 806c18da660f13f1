// The emulated WiFi link between the "uav" and "gcs" namespaces, measured with real UDP packets:
// delay, loss, rate, outage and teardown. Needs root (skips with the reason otherwise). The
// figures are printed for docs/deployment.md; the bands are wide for a noisy 2-core machine.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "EmulatedLink.hpp"
#include "TempDirTest.hpp"
#include "common/ChildProcess.hpp"

namespace uavslam::net {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

constexpr std::uint16_t kEchoPort = 9000;
constexpr std::uint16_t kSinkPort = 9001;

double to_ms(Clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

sockaddr_in socket_address(const std::string& ip, std::uint16_t port) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  inet_pton(AF_INET, ip.c_str(), &address.sin_addr);
  return address;
}

// A UDP socket of `host`'s namespace bound to its address and `port` (0: any).
int bound_udp(const EmulatedLink& link, Host host, std::uint16_t port) {
  const int fd = link.open_socket(host, SOCK_DGRAM);
  const sockaddr_in address = socket_address(link.address(host), port);
  if (bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    close(fd);
    throw std::runtime_error(std::string("bind: ") + std::strerror(errno));
  }
  return fd;
}

bool readable(int fd, int timeout_ms) {
  pollfd wait{fd, POLLIN, 0};
  return poll(&wait, 1, timeout_ms) > 0;
}

// Sends every datagram it receives back to its sender, on its own thread, until destroyed.
class UdpEcho {
 public:
  explicit UdpEcho(int fd) : fd_(fd), thread_([this] { serve(); }) {}
  ~UdpEcho() {
    stop_ = true;
    thread_.join();
    close(fd_);
  }

 private:
  void serve() {
    char buffer[2048];
    while (!stop_) {
      if (!readable(fd_, 20)) continue;
      sockaddr_in from{};
      socklen_t from_length = sizeof from;
      const ssize_t length =
          recvfrom(fd_, buffer, sizeof buffer, 0, reinterpret_cast<sockaddr*>(&from), &from_length);
      if (length > 0) {
        sendto(fd_, buffer, static_cast<std::size_t>(length), 0,
               reinterpret_cast<const sockaddr*>(&from), from_length);
      }
    }
  }

  int fd_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

struct Probes {
  std::vector<Clock::time_point> sent_at;
  std::vector<double> round_trip_ms;  // < 0: no answer
  int answered() const {
    return static_cast<int>(std::count_if(round_trip_ms.begin(), round_trip_ms.end(),
                                          [](double rtt) { return rtt >= 0.0; }));
  }
  double delivered_share() const {
    return static_cast<double>(answered()) / static_cast<double>(round_trip_ms.size());
  }
  // The p-th percentile (0..1) of the answered round trips.
  double percentile_ms(double p) const {
    std::vector<double> answered_rtts;
    for (double rtt : round_trip_ms) {
      if (rtt >= 0.0) answered_rtts.push_back(rtt);
    }
    if (answered_rtts.empty()) return -1.0;
    std::sort(answered_rtts.begin(), answered_rtts.end());
    return answered_rtts[static_cast<std::size_t>(p *
                                                  static_cast<double>(answered_rtts.size() - 1))];
  }
};

// Sends `count` numbered probes from uav to the gcs echo, one per `interval`, and records each
// answer's round trip; after the last, waits up to `drain` for late answers.
Probes send_probes(const EmulatedLink& link, int count, std::chrono::microseconds interval,
                   milliseconds drain = milliseconds(1000)) {
  const int fd = bound_udp(link, Host::kUav, 0);
  const sockaddr_in echo = socket_address(link.address(Host::kGcs), kEchoPort);
  Probes probes;
  probes.sent_at.resize(static_cast<std::size_t>(count));
  probes.round_trip_ms.assign(static_cast<std::size_t>(count), -1.0);
  int sent = 0;
  int answered = 0;
  Clock::time_point next_send = Clock::now();
  Clock::time_point drain_end = Clock::time_point::max();
  while (answered < count && Clock::now() < drain_end) {
    if (sent < count && Clock::now() >= next_send) {
      char probe[64] = {};
      std::memcpy(probe, &sent, sizeof sent);
      probes.sent_at[static_cast<std::size_t>(sent)] = Clock::now();
      sendto(fd, probe, sizeof probe, 0, reinterpret_cast<const sockaddr*>(&echo), sizeof echo);
      next_send += interval;
      if (++sent == count) drain_end = Clock::now() + drain;
    }
    if (!readable(fd, 1)) continue;
    char reply[64];
    if (recv(fd, reply, sizeof reply, 0) < static_cast<ssize_t>(sizeof(int))) continue;
    int seq = 0;
    std::memcpy(&seq, reply, sizeof seq);
    if (seq < 0 || seq >= sent || probes.round_trip_ms[static_cast<std::size_t>(seq)] >= 0.0) {
      continue;
    }
    probes.round_trip_ms[static_cast<std::size_t>(seq)] =
        to_ms(Clock::now() - probes.sent_at[static_cast<std::size_t>(seq)]);
    ++answered;
  }
  close(fd);
  return probes;
}

void print_probes(const std::string& what, const Probes& probes) {
  std::printf(
      "[figures] %s: %d/%zu answered (%.1f %%), round trip p50 %.1f ms, p90 %.1f ms, "
      "max %.1f ms\n",
      what.c_str(), probes.answered(), probes.round_trip_ms.size(),
      100.0 * probes.delivered_share(), probes.percentile_ms(0.5), probes.percentile_ms(0.9),
      probes.percentile_ms(1.0));
}

std::string command_output(const std::vector<std::string>& argv, const std::string& log) {
  process::ChildProcess child(argv, log);
  child.wait(std::chrono::seconds(10));
  return child.log();
}

class EmulatedLinkTest : public test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    const LinkAvailability availability = EmulatedLink::available(UAVSLAM_LINK_EMULATOR);
    if (!availability) GTEST_SKIP() << "two-host link not available: " << availability.reason;
  }

  std::unique_ptr<EmulatedLink> make_link(const LinkSpec& spec) {
    return std::make_unique<EmulatedLink>(spec, UAVSLAM_LINK_EMULATOR, dir.string());
  }

  // The output of a command run on the host (not in a namespace), such as `ip netns list`.
  std::string host_command(const std::vector<std::string>& argv) {
    return command_output(argv, path("command.log"));
  }
};

TEST_F(EmulatedLinkTest, TwentyMillisecondsEachWayGiveARoundTripOfAboutForty) {
  auto link = make_link({0.0, 20.0, 0.0, 0.0, 1});
  UdpEcho echo(bound_udp(*link, Host::kGcs, kEchoPort));
  const Probes probes = send_probes(*link, 200, milliseconds(10));
  print_probes("delay 20 ms each way", probes);
  std::printf("[figures] %s", link->stop_emulators().c_str());
  EXPECT_EQ(probes.answered(), 200);
  EXPECT_GE(probes.percentile_ms(0.5), 35.0);
  EXPECT_LE(probes.percentile_ms(0.5), 150.0);
  EXPECT_GE(probes.percentile_ms(0.0), 39.0);  // the delay is a floor: never early
}

TEST_F(EmulatedLinkTest, NoImpairmentDeliversEveryProbe) {
  auto link = make_link({});
  UdpEcho echo(bound_udp(*link, Host::kGcs, kEchoPort));
  const Probes probes = send_probes(*link, 2000, std::chrono::microseconds(1000));
  print_probes("no impairment", probes);
  EXPECT_EQ(probes.answered(), 2000);
  EXPECT_LT(probes.percentile_ms(0.5), 10.0);
}

TEST_F(EmulatedLinkTest, FivePercentLossEachWayAloneDropsItsShare) {
  auto link = make_link({0.0, 0.0, 0.0, 0.05, 1});
  UdpEcho echo(bound_udp(*link, Host::kGcs, kEchoPort));
  const Probes probes = send_probes(*link, 2000, std::chrono::microseconds(1000));
  print_probes("loss 5 % each way (iptables statistic)", probes);
  // Both ways: 0.95^2 = 90.25 % expected.
  EXPECT_GE(probes.delivered_share(), 0.80);
  EXPECT_LE(probes.delivered_share(), 0.99);
}

TEST_F(EmulatedLinkTest, DelayJitterAndFivePercentLossThroughTheEmulator) {
  auto link = make_link({20.0, 20.0, 5.0, 0.05, 7});
  UdpEcho echo(bound_udp(*link, Host::kGcs, kEchoPort));
  const Probes probes = send_probes(*link, 2000, std::chrono::microseconds(1000));
  print_probes("20 Mbit/s, delay 20 +- 5 ms and loss 5 % each way (link_emulator)", probes);
  std::printf("[figures] %s", link->stop_emulators().c_str());
  EXPECT_GE(probes.delivered_share(), 0.80);
  EXPECT_LE(probes.delivered_share(), 0.99);
  EXPECT_GE(probes.percentile_ms(0.5), 35.0);
  EXPECT_LE(probes.percentile_ms(0.5), 150.0);
}

// Received bytes over the time between the first and the last datagram of a burst far above the
// rate, sent from uav to gcs.
double burst_throughput_mbit(const EmulatedLink& link, int datagrams, std::size_t size) {
  const int sink = bound_udp(link, Host::kGcs, kSinkPort);
  const int sender = bound_udp(link, Host::kUav, 0);
  std::size_t bytes_after_first = 0;
  Clock::time_point first{};
  Clock::time_point last{};
  std::thread receiver([&] {
    std::vector<char> buffer(size);
    bool started = false;
    while (readable(sink, started ? 500 : 5000)) {  // the burst ends when the link goes quiet
      const ssize_t length = recv(sink, buffer.data(), buffer.size(), 0);
      if (length <= 0) continue;
      last = Clock::now();
      if (started) bytes_after_first += static_cast<std::size_t>(length);
      if (!started) first = last;
      started = true;
    }
  });
  const sockaddr_in to = socket_address(link.address(Host::kGcs), kSinkPort);
  const std::vector<char> payload(size, 'x');
  for (int i = 0; i < datagrams; ++i) {
    sendto(sender, payload.data(), payload.size(), 0, reinterpret_cast<const sockaddr*>(&to),
           sizeof to);
  }
  receiver.join();
  close(sender);
  close(sink);
  const double seconds = std::chrono::duration<double>(last - first).count();
  std::printf(
      "[figures] rate 20 Mbit/s: burst of %d x %zu B, %zu B received after the first in "
      "%.3f s\n",
      datagrams, size, bytes_after_first, seconds);
  return seconds > 0.0 ? static_cast<double>(bytes_after_first) * 8.0 / seconds / 1e6 : 0.0;
}

TEST_F(EmulatedLinkTest, RateLimitHoldsABurstToTwentyMegabits) {
  auto link = make_link({20.0, 0.0, 0.0, 0.0, 1});
  const double mbit = burst_throughput_mbit(*link, 2500, 1200);  // 3 MB: about 1.2 s at the rate
  std::printf("[figures] rate 20 Mbit/s: measured %.1f Mbit/s\n", mbit);
  EXPECT_LT(mbit, 1.5 * 20.0);
  EXPECT_GT(mbit, 0.5 * 20.0);
}

TEST_F(EmulatedLinkTest, NothingPassesDuringAnOutageAndTrafficResumesAfter) {
  auto link = make_link({20.0, 20.0, 0.0, 0.0, 1});
  UdpEcho echo(bound_udp(*link, Host::kGcs, kEchoPort));
  Probes probes;
  std::thread prober([&] { probes = send_probes(*link, 400, milliseconds(10)); });
  std::this_thread::sleep_for(milliseconds(1000));
  link->begin_outage();
  const Clock::time_point outage_begun = Clock::now();
  std::this_thread::sleep_for(milliseconds(2000));
  const Clock::time_point outage_ending = Clock::now();
  link->end_outage();
  const Clock::time_point outage_ended = Clock::now();
  prober.join();

  // A margin at each edge for probes already on their way when the rules changed.
  const auto margin = milliseconds(100);
  int before = 0, before_answered = 0, during = 0, during_answered = 0, after = 0,
      after_answered = 0;
  for (std::size_t i = 0; i < probes.sent_at.size(); ++i) {
    const Clock::time_point sent = probes.sent_at[i];
    const bool answered = probes.round_trip_ms[i] >= 0.0;
    if (sent + margin < outage_begun) {
      ++before;
      before_answered += answered;
    } else if (sent > outage_begun && sent + margin < outage_ending) {
      ++during;
      during_answered += answered;
    } else if (sent > outage_ended + margin) {
      ++after;
      after_answered += answered;
    }
  }
  std::printf("[figures] 2 s outage: answered before %d/%d, during %d/%d, after %d/%d\n",
              before_answered, before, during_answered, during, after_answered, after);
  EXPECT_GT(during, 100);
  EXPECT_EQ(during_answered, 0);
  EXPECT_GT(before_answered, 0.9 * before);
  EXPECT_GT(after, 30);
  EXPECT_GT(after_answered, 0.9 * after);
}

TEST_F(EmulatedLinkTest, LoopbackWorksInsideANamespaceAndCommandsRunThere) {
  auto link = make_link({20.0, 20.0, 0.0, 0.05, 1});
  const int server = link->open_socket(Host::kUav, SOCK_DGRAM);
  const sockaddr_in loopback = socket_address("127.0.0.1", kEchoPort);
  ASSERT_EQ(bind(server, reinterpret_cast<const sockaddr*>(&loopback), sizeof loopback), 0);
  const int client = link->open_socket(Host::kUav, SOCK_DGRAM);
  const char hello[] = "hello";
  sendto(client, hello, sizeof hello, 0, reinterpret_cast<const sockaddr*>(&loopback),
         sizeof loopback);
  ASSERT_TRUE(readable(server, 2000));
  char received[16] = {};
  EXPECT_EQ(recv(server, received, sizeof received, 0), static_cast<ssize_t>(sizeof hello));
  EXPECT_STREQ(received, hello);
  close(client);
  close(server);

  std::vector<std::string> argv = link->exec_prefix(Host::kGcs);
  argv.insert(argv.end(), {argv.front(), "-br", "addr", "show", "dev", "gcs0"});
  EXPECT_NE(host_command(argv).find("10.200.0.2/24"), std::string::npos);
}

TEST_F(EmulatedLinkTest, TeardownRemovesEverythingAlsoWhenTheBodyThrows) {
  const std::string ip = EmulatedLink::tool_path("ip");
  // The host's INPUT and OUTPUT chains, which a misplaced rule of ours would land in (other
  // programs, such as container networking, change FORWARD and nat while we run).
  const std::string iptables = EmulatedLink::tool_path("iptables");
  const std::string iptables_before =
      host_command({iptables, "-S", "INPUT"}) + host_command({iptables, "-S", "OUTPUT"});
  std::string uav_namespace, gcs_namespace;
  try {
    auto link = make_link({20.0, 20.0, 0.0, 0.05, 1});
    link->begin_outage();
    uav_namespace = link->namespace_name(Host::kUav);
    gcs_namespace = link->namespace_name(Host::kGcs);
    ASSERT_NE(host_command({ip, "netns", "list"}).find(uav_namespace), std::string::npos);
    throw std::runtime_error("the test body fails");
  } catch (const std::runtime_error&) {
  }
  const std::string namespaces = host_command({ip, "netns", "list"});
  EXPECT_EQ(namespaces.find(uav_namespace), std::string::npos) << namespaces;
  EXPECT_EQ(namespaces.find(gcs_namespace), std::string::npos) << namespaces;
  const std::string links = host_command({ip, "-br", "link"});
  EXPECT_EQ(links.find("uav0"), std::string::npos) << links;
  EXPECT_EQ(links.find("gcs0"), std::string::npos) << links;
  EXPECT_EQ(host_command({iptables, "-S", "INPUT"}) + host_command({iptables, "-S", "OUTPUT"}),
            iptables_before);
  // The emulators were stopped and reaped: this process has no child left.
  EXPECT_EQ(waitpid(-1, nullptr, WNOHANG), -1);
}

TEST_F(EmulatedLinkTest, SweepRemovesNamespacesOfDeadRunsOnly) {
  const pid_t dead = fork();
  if (dead == 0) _exit(0);
  ASSERT_GT(dead, 0);
  waitpid(dead, nullptr, 0);
  const std::string ip = EmulatedLink::tool_path("ip");
  const std::string stale = "usl" + std::to_string(dead) + "n0u";
  const std::string ours = "usl" + std::to_string(getpid()) + "n99u";
  host_command({ip, "netns", "add", stale});
  host_command({ip, "netns", "add", ours});
  const std::vector<std::string> removed = EmulatedLink::sweep_stale();
  const std::string namespaces = host_command({ip, "netns", "list"});
  host_command({ip, "netns", "delete", ours});
  EXPECT_NE(std::find(removed.begin(), removed.end(), stale), removed.end());
  EXPECT_EQ(namespaces.find(stale), std::string::npos) << namespaces;
  EXPECT_NE(namespaces.find(ours), std::string::npos) << namespaces;
}

}  // namespace
}  // namespace uavslam::net
