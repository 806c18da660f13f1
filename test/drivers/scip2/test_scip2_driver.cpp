// lidar_driver --source scip2:... / scip2tcp:... against scip2_emulator (a UTM-30LX on a
// pseudo-terminal or TCP 127.0.0.1), the test subscribing to `scan` on its own domains 194-196:
// scans at 40 Hz with the emulator's 1080 ranges, stamps within 3 ms of the emulator's true time
// although its clock runs 100 ppm fast and wraps, faults counted while streaming continues, and a
// silence and a disconnect survived by the same process.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <fstream>
#include <limits>
#include <mutex>
#include <regex>
#include <sstream>
#include <vector>

#include <msg/LaserScanPubSubTypes.h>

#include "ProcessTest.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "io/ScenarioFile.hpp"
#include "sim/FlightSimulator.hpp"

namespace uavslam::test {
namespace {

using namespace std::chrono_literals;

constexpr double kPi = 3.14159265358979323846;
const std::string kScenario = std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/short.yaml";

struct ReceivedScan {
  double stamp = 0.0;
  std::vector<float> ranges;
  std::size_t intensities = 0;
  float angle_min = 0.0f;
  float angle_increment = 0.0f;
  float time_increment = 0.0f;
};

struct TruthLine {
  std::uint64_t index = 0;
  double true_time = 0.0;
  std::uint32_t stamp_ms = 0;
  std::size_t sim_scan = 0;
};

// The test's `scan` subscriber on `domain`, keeping every scan.
class ScanCollector {
 public:
  explicit ScanCollector(int domain)
      : participant_(domain, dds::default_profiles_path(), "uavslam_loopback", "scip2_test"),
        reader_(participant_, dds::topic_name("uav1", dds::kScanTopic), "sensor_reader",
                [this](const msg::LaserScan& m, const auto&) { keep(m); }) {}

  bool wait_for(std::size_t count, std::chrono::seconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return scans_.size() >= count; });
  }
  std::vector<ReceivedScan> scans() {
    std::lock_guard<std::mutex> lock(mutex_);
    return scans_;
  }

 private:
  void keep(const msg::LaserScan& m) {
    ReceivedScan scan{dds::from_msg_time(m.header().stamp()),
                      m.ranges(),
                      m.intensities().size(),
                      m.angle_min(),
                      m.angle_increment(),
                      m.time_increment()};
    std::lock_guard<std::mutex> lock(mutex_);
    scans_.push_back(std::move(scan));
    changed_.notify_all();
  }

  dds::Participant participant_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<ReceivedScan> scans_;
  dds::Reader<msg::LaserScanPubSubType> reader_;
};

std::vector<TruthLine> read_truth(const std::string& path) {
  std::vector<TruthLine> lines;
  std::ifstream in(path);
  TruthLine t;
  while (in >> t.index >> t.true_time >> t.stamp_ms >> t.sim_scan) lines.push_back(t);
  return lines;
}

const std::vector<std::vector<float>>& simulated_scans() {
  static const std::vector<std::vector<float>> scans = [] {
    sim::FlightSimulator simulator(io::load_scenario(kScenario));
    std::vector<std::vector<float>> all;
    Scan scan;
    while (simulator.next_scan(scan)) all.push_back(scan.ranges);
    return all;
  }();
  return scans;
}

// The range the driver should publish for a simulated range (the emulator sends whole mm; what
// is not a return, or below the UTM-30LX's 23 mm, is no return).
float expected_range(float simulated) {
  if (!std::isfinite(simulated)) return std::numeric_limits<float>::infinity();
  const double mm = std::round(static_cast<double>(simulated) * 1000.0);
  if (mm < 23.0 || mm > 60000.0) return std::numeric_limits<float>::infinity();
  return static_cast<float>(mm * 1e-3);
}

// The truth line nearest in time to `stamp`.
const TruthLine& nearest(const std::vector<TruthLine>& truth, double stamp) {
  return *std::min_element(truth.begin(), truth.end(), [&](const TruthLine& a, const TruthLine& b) {
    return std::abs(a.true_time - stamp) < std::abs(b.true_time - stamp);
  });
}

// The numbers in lidar_driver's last status line.
struct DriverStatus {
  long checksum_errors = -1, garbage_bytes = -1, damaged = -1, reconnects = -1;
};

DriverStatus last_status(const std::string& log) {
  static const std::regex line(
      R"(scip2 status: .* (\d+) checksum errors, (\d+) garbage bytes, (\d+) damaged scans, (\d+) reconnects)");
  DriverStatus status;
  for (auto it = std::sregex_iterator(log.begin(), log.end(), line); it != std::sregex_iterator();
       ++it) {
    status = {std::stol((*it)[1]), std::stol((*it)[2]), std::stol((*it)[3]), std::stol((*it)[4])};
  }
  return status;
}

class Scip2Driver : public ProcessTest {
 protected:
  static std::string emulator() { return UAVSLAM_SCIP2_EMULATOR; }

  std::vector<std::string> emulator_argv(const std::vector<std::string>& extra) {
    std::vector<std::string> argv{emulator(), "--scenario", kScenario, "--truth",
                                  path("truth.txt")};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return argv;
  }

  // Every received scan against the emulator's truth: its largest stamp error (s).
  double check_against_truth(const std::vector<ReceivedScan>& scans) {
    const std::vector<TruthLine> truth = read_truth(path("truth.txt"));
    EXPECT_FALSE(truth.empty());
    if (truth.empty()) return INFINITY;
    double worst = 0.0;
    for (const ReceivedScan& scan : scans) {
      const TruthLine& t = nearest(truth, scan.stamp);
      worst = std::max(worst, std::abs(scan.stamp - t.true_time));
      const std::vector<float>& simulated = simulated_scans().at(t.sim_scan);
      EXPECT_EQ(scan.ranges.size(), 1080u);
      if (scan.ranges.size() != simulated.size()) continue;
      std::size_t different = 0;
      for (std::size_t i = 0; i < simulated.size(); ++i) {
        const float expected = expected_range(simulated[i]);
        const bool same = std::isinf(expected) ? std::isinf(scan.ranges[i])
                                               : std::abs(scan.ranges[i] - expected) < 1e-4f;
        different += same ? 0 : 1;
      }
      EXPECT_EQ(different, 0u) << "scan matched to emulator scan " << t.index;
    }
    return worst;
  }
};

TEST_F(Scip2Driver, PtyScansMatchTheEmulatorWithin3msDespite100PpmDrift) {
  // The sensor clock starts 5 s before its 24-bit wrap and runs 100 ppm fast.
  process::ChildProcess sensor(
      emulator_argv({"--pty-link", path("ttyACM0"), "--drift-ppm", "100", "--offset-ms",
                     std::to_string((1 << 24) - 5000), "--jitter-ms", "2"}),
      log_path("emulator"));
  ASSERT_TRUE(wait_for_log(sensor, "ready on", 60s)) << sensor.log();
  ScanCollector scans(194);
  process::ChildProcess driver(
      node_argv("lidar_driver", 194,
                {"--source", "scip2:" + path("ttyACM0"), "--status-period", "1"}),
      log_path("lidar_driver"));
  ASSERT_TRUE(scans.wait_for(400, 60s)) << driver.log();  // 10 s: across the wrap
  const std::vector<ReceivedScan> received = scans.scans();

  EXPECT_NEAR(received.front().angle_min, -135.0 * kPi / 180.0, 1e-6);
  EXPECT_NEAR(received.front().angle_increment, 0.25 * kPi / 180.0, 1e-7);
  // A step of the 1440 in the 25 ms turn: when each beam fired, for the matcher's deskew.
  EXPECT_NEAR(received.front().time_increment, 0.025 / 1440, 1e-9);
  EXPECT_EQ(received.front().intensities, 1080u);
  std::vector<double> intervals;
  for (std::size_t i = 1; i < received.size(); ++i) {
    intervals.push_back(received[i].stamp - received[i - 1].stamp);
  }
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  EXPECT_NEAR(intervals[intervals.size() / 2], 0.025, 0.001);  // 40 Hz

  const double worst = check_against_truth(received);
  RecordProperty("worst_stamp_error_ms", std::to_string(worst * 1e3));
  std::cerr << "worst stamp error " << worst * 1e3 << " ms over " << received.size() << " scans\n";
  EXPECT_LT(worst, 0.003);
  EXPECT_THAT(driver.log(), ::testing::HasSubstr("clock: best TM round trip"));
  EXPECT_EQ(driver.stop(10s), 0) << driver.log();
}

TEST_F(Scip2Driver, TcpFaultsAreCountedAndStreamingContinues) {
  process::ChildProcess sensor(emulator_argv({"--tcp-port", "0", "--bad-checksum-every", "2000",
                                              "--garbage-every", "30", "--truncate-every", "70"}),
                               log_path("emulator"));
  ASSERT_TRUE(wait_for_log(sensor, "ready on", 60s)) << sensor.log();
  std::smatch port;
  const std::string log = sensor.log();
  ASSERT_TRUE(std::regex_search(log, port, std::regex(R"(127\.0\.0\.1:(\d+))"))) << log;
  ScanCollector scans(195);
  process::ChildProcess driver(
      node_argv("lidar_driver", 195,
                {"--source", "scip2tcp:127.0.0.1:" + port[1].str(), "--status-period", "1"}),
      log_path("lidar_driver"));
  ASSERT_TRUE(scans.wait_for(300, 60s)) << driver.log();
  ASSERT_TRUE(wait_for_log(driver, "scip2 status", 30s));
  check_against_truth(scans.scans());  // every scan published is a whole, correct one
  EXPECT_EQ(driver.stop(10s), 0) << driver.log();
  const DriverStatus status = last_status(driver.log());
  std::cerr << "checksum errors " << status.checksum_errors << ", garbage bytes "
            << status.garbage_bytes << ", damaged scans " << status.damaged << ", reconnects "
            << status.reconnects << "\n";
  EXPECT_GT(status.checksum_errors, 0);
  EXPECT_GT(status.garbage_bytes, 0);
  EXPECT_GT(status.damaged, 0);
  EXPECT_EQ(status.reconnects, 0);  // faults in the data are not a lost sensor
}

TEST_F(Scip2Driver, SilenceThenDisconnectReconnectsWithoutRestarting) {
  process::ChildProcess sensor(
      emulator_argv({"--pty-link", path("ttyACM0"), "--silence-at", "4", "--silence-for", "2",
                     "--disconnect-at", "10", "--disconnect-for", "1.5"}),
      log_path("emulator"));
  ASSERT_TRUE(wait_for_log(sensor, "ready on", 60s)) << sensor.log();
  ScanCollector scans(196);
  process::ChildProcess driver(
      node_argv("lidar_driver", 196,
                {"--source", "scip2:" + path("ttyACM0"), "--status-period", "1"}),
      log_path("lidar_driver"));
  ASSERT_TRUE(wait_for_log(sensor, "reconnecting", 60s)) << sensor.log();
  const std::size_t before = scans.scans().size();
  // Scans flow again, published by the same process: 2 s worth after the pty came back.
  ASSERT_TRUE(scans.wait_for(before + 80, 60s)) << driver.log();
  EXPECT_TRUE(driver.running());
  const std::string log = driver.log();
  EXPECT_THAT(log, ::testing::HasSubstr("no scan for"));
  EXPECT_THAT(log, ::testing::HasSubstr("the device closed the link"));
  EXPECT_GE(std::count(log.begin(), log.end(), '\n'), 3);
  EXPECT_GE(last_status(log).reconnects, 2);

  // How long after the pty came back the first scan was stamped (reported, not asserted).
  const std::vector<TruthLine> truth = read_truth(path("truth.txt"));
  const std::vector<ReceivedScan> received = scans.scans();
  const double back = truth.front().true_time + 11.5;
  double first_after = INFINITY;
  for (const ReceivedScan& s : received) {
    if (s.stamp > back) first_after = std::min(first_after, s.stamp);
  }
  std::cerr << "first scan " << (first_after - back) << " s after the device came back\n";
  RecordProperty("reconnect_s", std::to_string(first_after - back));
  EXPECT_EQ(driver.stop(10s), 0) << driver.log();
}

}  // namespace
}  // namespace uavslam::test
