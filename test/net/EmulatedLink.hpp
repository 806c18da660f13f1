// Two hosts on one machine for the two-host tests: network namespaces "uav" and "gcs" (unique
// names per object, usl<pid>n<k>u / usl<pid>n<k>g) joined by a veth pair uav0 (10.200.0.1/24) and
// gcs0 (10.200.0.2/24), with `lo` up in both, and an emulated WiFi link between them:
//  - rate: a tbf qdisc on both veth ends;
//  - one-way delay (+ jitter, + loss): iptables in each namespace sends what leaves its veth to
//    an NFQUEUE served by link_emulator, started inside that namespace;
//  - loss alone: iptables `-m statistic --mode random` drops that share of what arrives;
//  - outage: every packet arriving on either veth is dropped until it ends;
//  - traffic: the emulators also count the bytes of each DDS topic leaving their side.
// This kernel has no netem. All rules live inside the two namespaces, never in the host's own
// tables; deleting the namespaces removes the veths, qdiscs and rules with them. The destructor
// does that (and stops the emulators), also when a test fails or throws. Needs root.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace uavslam::process {
class ChildProcess;
}

namespace uavslam::net {

enum class Host { kUav, kGcs };

// The WiFi link, the same in both directions. Zero means "not impaired".
struct LinkSpec {
  double rate_mbit = 0.0;  // tbf rate limit of each veth end
  double delay_ms = 0.0;   // one-way delay of each direction
  double jitter_ms = 0.0;  // delay spread, +-; packets keep their order
  double loss = 0.0;       // share of packets lost in each direction, 0..1
  std::uint64_t seed = 1;  // seeds the emulator's losses (with delay; the uav side uses seed + 1)
  // Per-topic bytes of each direction (link_emulator --traffic; traffic_file): starts the
  // emulators even without delay (they then also make the losses, instead of iptables).
  bool record_traffic = false;
};

struct LinkAvailability {
  bool ok = false;
  std::string reason;  // why not, for GTEST_SKIP
  explicit operator bool() const { return ok; }
};

class EmulatedLink {
 public:
  // Whether this machine can build the link: root, `ip`, `tc`, `iptables`, a namespace that can
  // take an NFQUEUE rule, the NFQUEUE kernel module and the emulator binary at `emulator_path`.
  static LinkAvailability available(const std::string& emulator_path);

  // Deletes usl* namespaces whose creating process is gone (a crashed earlier run), killing what
  // still runs in them. Returns the names removed. The constructor calls it.
  static std::vector<std::string> sweep_stale();

  // Where `ip`, `tc` or `iptables` is (PATH, then /usr/sbin and /sbin); empty if missing.
  static std::string tool_path(const std::string& name);

  // Builds both namespaces and the link; throws std::runtime_error naming the failed command
  // (after removing what it had built). Emulator logs go to `log_dir`.
  EmulatedLink(const LinkSpec& spec, const std::string& emulator_path, const std::string& log_dir);
  EmulatedLink(const EmulatedLink&) = delete;
  EmulatedLink& operator=(const EmulatedLink&) = delete;
  ~EmulatedLink();

  const std::string& namespace_name(Host host) const;
  std::string interface_name(Host host) const;  // "uav0" / "gcs0"
  std::string address(Host host) const;         // "10.200.0.1" / "10.200.0.2"

  // `ip netns exec NAME`: put it before a command's argv to run it inside `host`'s namespace
  // (e.g. for process::ChildProcess, whose argv[0] must be a path).
  std::vector<std::string> exec_prefix(Host host) const;

  // A socket (socket(AF_INET, type, 0)) that lives in `host`'s namespace although this process
  // does not; the caller owns the descriptor. Throws on failure.
  int open_socket(Host host, int type) const;

  // Drops every packet arriving on either veth (both directions) until end_outage().
  void begin_outage();
  void end_outage();
  // begin_outage, `length`, end_outage.
  void outage(std::chrono::milliseconds length);

  // Stops the link emulators (they print their counters) and returns their output, uav first;
  // empty when none runs (no delay, jitter or record_traffic). Later calls return the same text.
  std::string stop_emulators();

  // The JSON file of what `from` put on the link, per DDS topic (link_emulator --traffic), written
  // when stop_emulators() returns; empty when the spec does not record traffic.
  std::string traffic_file(Host from) const;

 private:
  struct Tools {
    std::string ip, tc, iptables;
  };
  static Tools find_tools();

  void build(const LinkSpec& spec, const std::string& emulator_path, const std::string& log_dir);
  void start_emulator(Host host, const LinkSpec& spec, const std::string& emulator_path,
                      const std::string& log_dir);
  void iptables(Host host, const std::vector<std::string>& rule) const;
  void tear_down() noexcept;

  Tools tools_;
  std::string uav_namespace_;
  std::string gcs_namespace_;
  std::vector<std::unique_ptr<process::ChildProcess>> emulators_;
  std::string emulator_output_;
  std::string uav_traffic_file_;
  std::string gcs_traffic_file_;
  bool outage_active_ = false;
};

}  // namespace uavslam::net
