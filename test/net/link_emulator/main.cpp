// link_emulator: the delay and loss of a WiFi link for the two-host tests (this kernel has no
// netem). iptables rules send packets to an NFQUEUE; this program holds each for the one-way
// delay, drops a seeded share, and then lets the rest go. Runs inside the network namespace
// whose packets it delays (`ip netns exec NAME link_emulator ...`).
//
//   iptables -A OUTPUT -o uav0 -j NFQUEUE --queue-num 1
//   link_emulator --queue 1 --delay-ms 20 --loss 0.05 --seed 7
//
// `--traffic FILE`: every packet is also parsed as RTPS (RtpsTraffic) and, at exit, FILE gets the
// bytes each DDS topic put on the link, counted before the loss decision (what the sender sent):
//   {"duration_s", "active_s", "total_bytes", "total_packets",
//    "topics": {"uav1/scan": {"bytes", "bytes_per_s", "packets_share", "data", "fragments"}, ...}}
//
// Prints "link_emulator: queue N ready" once bound; on SIGINT/SIGTERM (or when its parent ends)
// lets the held packets go, prints its counters (and writes the traffic file) and exits 0. Exit 1:
// cannot bind the queue; 2: bad arguments.
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "DelayLine.hpp"
#include "NetfilterQueue.hpp"
#include "RtpsTraffic.hpp"

namespace {

using uavslam::net::DelayLine;
using uavslam::net::LinkImpairment;
using uavslam::net::NetfilterQueue;
using uavslam::net::RtpsTraffic;

struct Options {
  std::uint16_t queue = 0;
  std::uint32_t max_queue_length = 20000;
  double delay_ms = 0.0;
  double jitter_ms = 0.0;
  double loss = 0.0;
  std::uint64_t seed = 1;
  std::string traffic_file;  // empty: packets are not looked into
};

using Clock = std::chrono::steady_clock;

// The link's traffic and when it went by.
struct TrafficRecord {
  RtpsTraffic traffic;
  Clock::time_point started = Clock::now();
  std::optional<Clock::time_point> first_packet, last_packet;

  void add(const std::uint8_t* packet, std::size_t length) {
    const Clock::time_point now = Clock::now();
    if (!first_packet) first_packet = now;
    last_packet = now;
    traffic.add_packet(packet, length);
  }
};

double seconds(Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

// Written to FILE.tmp and renamed: whoever reads FILE never sees half of it.
void write_traffic(const std::string& file, const TrafficRecord& record) {
  const double duration = seconds(Clock::now() - record.started);
  nlohmann::json topics = nlohmann::json::object();
  for (const auto& [name, topic] : record.traffic.topics()) {
    topics[name] = {{"bytes", topic.bytes},
                    {"bytes_per_s", duration > 0.0 ? topic.bytes / duration : 0.0},
                    {"packets_share", topic.packets_share},
                    {"data", topic.data},
                    {"fragments", topic.fragments}};
  }
  const nlohmann::json out = {
      {"duration_s", duration},
      {"active_s", record.first_packet ? seconds(*record.last_packet - *record.first_packet) : 0.0},
      {"total_bytes", record.traffic.total_bytes()},
      {"total_packets", record.traffic.total_packets()},
      {"topics", topics}};
  const std::string partial = file + ".tmp";
  {
    std::ofstream stream(partial);
    stream << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    if (!stream) throw std::runtime_error("cannot write " + partial);
  }
  std::filesystem::rename(partial, file);
}

std::chrono::microseconds from_ms(double ms) {
  return std::chrono::microseconds(static_cast<std::int64_t>(ms * 1000.0));
}

// SIGINT and SIGTERM arrive as readable data on the returned descriptor, so the packet loop waits
// on both in one poll and never misses a stop request.
int stop_signals_fd() {
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  sigprocmask(SIG_BLOCK, &stop, nullptr);
  return signalfd(-1, &stop, SFD_CLOEXEC);
}

// Milliseconds until `due`, rounded up so the packet is never released early; -1 waits forever.
int poll_timeout_ms(const DelayLine& line) {
  const auto due = line.next_due();
  if (!due) return -1;
  const auto wait = std::chrono::ceil<std::chrono::milliseconds>(*due - DelayLine::Clock::now());
  return wait.count() < 0 ? 0 : static_cast<int>(wait.count());
}

int run(const Options& options) {
  const int stop_fd = stop_signals_fd();
  // The emulator must not outlive the test that started it (it would keep its namespace alive).
  prctl(PR_SET_PDEATHSIG, SIGTERM);

  DelayLine line(LinkImpairment{from_ms(options.delay_ms), from_ms(options.jitter_ms), options.loss,
                                options.seed});
  const bool record_traffic = !options.traffic_file.empty();
  TrafficRecord record;
  NetfilterQueue queue(options.queue, options.max_queue_length, record_traffic,
                       [&](std::uint32_t id, const std::uint8_t* packet, std::size_t length) {
                         // Counted before the loss decision: what the sender put on the link.
                         if (record_traffic && packet != nullptr) record.add(packet, length);
                         return line.admit(id, DelayLine::Clock::now());
                       });
  std::cout << "link_emulator: queue " << options.queue << " ready (delay " << options.delay_ms
            << " ms, jitter " << options.jitter_ms << " ms, loss " << options.loss << ", seed "
            << options.seed << ")" << std::endl;

  bool stopping = false;
  while (!stopping) {
    pollfd waits[2] = {{queue.fd(), POLLIN, 0}, {stop_fd, POLLIN, 0}};
    poll(waits, 2, poll_timeout_ms(line));
    if (waits[0].revents & POLLIN) queue.receive();
    for (std::uint32_t id : line.release_due(DelayLine::Clock::now())) queue.accept(id);
    stopping = (waits[1].revents & POLLIN) != 0;
  }
  for (std::uint32_t id : line.release_all()) queue.accept(id);

  const auto& counters = line.counters();
  const auto drops = queue.drops();
  std::cout << "link_emulator: packets " << counters.packets << ", dropped " << counters.lost
            << ", max held " << counters.max_held << ", queue-full drops " << drops.queue_full
            << ", undelivered " << drops.undelivered << std::endl;
  if (record_traffic) {
    write_traffic(options.traffic_file, record);
    std::cout << "link_emulator: traffic of " << record.traffic.total_packets() << " packets, "
              << record.traffic.total_bytes() << " bytes in " << options.traffic_file << std::endl;
  }
  close(stop_fd);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Holds the packets of an NFQUEUE for a one-way delay and drops a seeded share: the WiFi "
      "link of the two-host tests. Run it inside the namespace whose iptables rules send packets "
      "to the queue (-j NFQUEUE --queue-num N). Stops on SIGINT/SIGTERM or when its parent ends, "
      "printing packets, dropped and max held."};
  Options options;
  app.add_option("--queue", options.queue, "NFQUEUE number to bind")->capture_default_str();
  app.add_option("--delay-ms", options.delay_ms, "one-way delay added to every packet")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--jitter-ms", options.jitter_ms,
                 "delay spread uniformly over +-this (packets keep their order)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--loss", options.loss, "share of packets dropped, 0..1")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--seed", options.seed, "seed of the loss and jitter draws")
      ->capture_default_str();
  app.add_option("--max-queue-len", options.max_queue_length,
                 "packets the kernel may hold for us; beyond it drops them and counts")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--traffic", options.traffic_file,
                 "write the bytes each DDS topic put on the link to this JSON file at exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help is a "parse error" with exit code 0
  }
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::cerr << "link_emulator: " << e.what() << std::endl;
    return 1;
  }
}
