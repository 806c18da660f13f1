// Per-topic bytes on the emulated WiFi link (issue 6): lidar_driver on the UAV publishes the short
// flight's 801 scans at 4x real time to a ground station across the link (20 Mbit/s, 20 ms, 5 %
// loss), and link_emulator --traffic attributes what each side put on the link to DDS topics.
// The UAV's side must be mostly uav1/scan, about scans x their serialized size, and the topics
// must add up to every byte the emulator saw. Needs root; skips with the reason otherwise.
#include <cmath>
#include <fstream>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <msg/LaserScanPubSubTypes.h>
#include <nlohmann/json.hpp>

#include "EmulatedLink.hpp"
#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"
#include "dds/SimulatedSensorMessages.hpp"

namespace uavslam {
namespace {

using namespace std::chrono_literals;
using net::Host;

const std::string kScenario = std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/short.yaml";
constexpr long kScans = 801;  // the short flight: 20 s at 40 Hz
constexpr int kDomain = 209;
constexpr double kDatagram = 1400.0;  // maxMessageSize of the link transports
// A scan datagram's headers besides its fragment: IPv4 20, UDP 8, RTPS 20, INFO_DST 16, INFO_TS
// 12, DATA_FRAG 36, and the 60-byte vendor submessage (0x80) Fast DDS's statistics build adds to
// every datagram (172, seen with tcpdump), with room to spare.
constexpr double kDatagramHeaders = 200.0;

// A simulated scan's CDR size as lidar_driver publishes it (encapsulation included): 1080 beams,
// frame "laser", vehicle "uav1", no intensities.
std::size_t serialized_scan_bytes() {
  Scan scan;
  scan.ranges.assign(LidarSpec{}.beams, 5.0f);
  msg::LaserScan message = dds::simulated_scan_message(scan, LidarSpec{}, "uav1");
  msg::LaserScanPubSubType type;
  return type.getSerializedSizeProvider(&message)();
}

// The first "packets N" of the emulators' output: the UAV side's count (it is printed first).
long emulator_packets(const std::string& output) {
  std::smatch match;
  if (!std::regex_search(output, match, std::regex("link_emulator: packets (\\d+)"))) return -1;
  return std::stol(match[1]);
}

nlohmann::json read_json(const std::string& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

class LinkTraffic : public test::ProcessTest {
 protected:
  void SetUp() override {
    ProcessTest::SetUp();
    const net::LinkAvailability can = net::EmulatedLink::available(UAVSLAM_LINK_EMULATOR);
    if (!can) GTEST_SKIP() << "two hosts cannot be emulated here: " << can.reason;
    net::LinkSpec spec;
    spec.rate_mbit = 20.0;
    spec.delay_ms = 20.0;
    spec.loss = 0.05;
    spec.record_traffic = true;
    link_ = std::make_unique<net::EmulatedLink>(spec, UAVSLAM_LINK_EMULATOR, dir.string());
  }

  void TearDown() override {
    processes_.clear();  // stopped before their namespaces go
    link_.reset();
    ProcessTest::TearDown();
  }

  process::ChildProcess& start(Host host, const std::string& name,
                               const std::vector<std::string>& flags) {
    std::vector<std::string> argv = link_->exec_prefix(host);
    const std::vector<std::string> node = node_argv(name, kDomain, flags);
    argv.insert(argv.end(), node.begin(), node.end());
    argv.insert(argv.end(), {"--participant-profile",
                             host == Host::kUav ? "uavslam_link_uav" : "uavslam_link_gcs"});
    processes_.push_back(std::make_unique<process::ChildProcess>(argv, log_path(name)));
    EXPECT_TRUE(processes_.back()->started()) << name;
    return *processes_.back();
  }

  std::unique_ptr<net::EmulatedLink> link_;
  std::vector<std::unique_ptr<process::ChildProcess>> processes_;
};

TEST_F(LinkTraffic, ScansTakeTheUavSideOfTheLinkAndTopicsAddUpToIt) {
  process::ChildProcess& station = start(Host::kGcs, "ground_station", {"--out", path("gcs")});
  process::ChildProcess& lidar =
      start(Host::kUav, "lidar_driver", sensor_flags(kScenario, shared_start_time()));
  ASSERT_TRUE(lidar.wait(60s)) << lidar.log();
  ASSERT_EQ(lidar.exit_code(), 0) << lidar.log() << station.log();
  ASSERT_EQ(station.stop(10s), 0) << station.log();
  const std::string emulators = link_->stop_emulators();

  const nlohmann::json uav = read_json(link_->traffic_file(Host::kUav));
  const nlohmann::json gcs = read_json(link_->traffic_file(Host::kGcs));
  std::cerr << "uav -> gcs: " << uav.dump(2) << "\ngcs -> uav: " << gcs.dump(2) << "\n";

  // Every byte the emulator saw is some topic's (or discovery's, or other's).
  for (const nlohmann::json* side : {&uav, &gcs}) {
    std::uint64_t bytes = 0;
    double packets = 0.0;
    for (const auto& [name, topic] : (*side)["topics"].items()) {
      bytes += topic["bytes"].get<std::uint64_t>();
      packets += topic["packets_share"].get<double>();
    }
    EXPECT_EQ(bytes, (*side)["total_bytes"].get<std::uint64_t>());
    EXPECT_NEAR(packets, (*side)["total_packets"].get<double>(), 1e-3);
  }
  EXPECT_EQ(uav["total_packets"].get<long>(), emulator_packets(emulators)) << emulators;

  // The scans: each sent once (BEST_EFFORT; counted before the link's losses) in datagrams of at
  // most 1400 bytes, each with at most kDatagramHeaders of headers.
  ASSERT_TRUE(uav["topics"].contains("uav1/scan")) << uav.dump();
  const nlohmann::json& scan = uav["topics"]["uav1/scan"];
  const auto scan_bytes = scan["bytes"].get<double>();
  const auto fragments = scan["fragments"].get<double>();
  const double sample = static_cast<double>(serialized_scan_bytes());
  const double payload = kScans * sample;
  std::cerr << "scan: " << sample << " serialized bytes, " << fragments / kScans
            << " datagrams and " << scan_bytes / kScans << " bytes on the link per scan ("
            << (scan_bytes - payload) / fragments << " bytes of headers per datagram)\n";
  EXPECT_GE(fragments, kScans * std::ceil(sample / kDatagram));
  EXPECT_GT(scan_bytes, payload);
  EXPECT_LE(scan_bytes, payload + fragments * kDatagramHeaders);
  EXPECT_GT(scan_bytes, 0.9 * uav["total_bytes"].get<double>());
  EXPECT_FALSE(uav["topics"].contains("unknown")) << "every writer was named by its SEDP data";
}

}  // namespace
}  // namespace uavslam
