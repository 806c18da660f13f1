// The matcher falling behind: the sensors publish the short flight at 4x real time (160 scans/s)
// to a matcher made slow on purpose (brute-force search, 40 iterations: tens of ms per scan). It
// must keep to fresh scans, skipping and counting those more than its backlog (0.25 s of sensor
// time) behind the newest, never queue them all: so it reaches the flight's last scan soon after
// the LiDAR stops (a queue would take minutes to drain) and its memory stays bounded.
#include <sys/types.h>

#include <chrono>
#include <condition_variable>
#include <fstream>
#include <iostream>
#include <mutex>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <msg/MatcherStatusPubSubTypes.h>

#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"

namespace uavslam {
namespace {

using namespace std::chrono_literals;

constexpr int kDomain = 186;              // this test's own DDS domain
constexpr std::uint64_t kLastScan = 800;  // short.yaml: 20 s at 40 Hz, sequences 0..800
const std::string kScenario = std::string(UAVSLAM_SOURCE_DIR) + "/config/scenarios/short.yaml";

// Peak resident memory of a process in kB (VmHWM in /proc/<pid>/status), 0 if unreadable.
long peak_rss_kb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  long value = 0;
  while (status >> key) {
    if (key == "VmHWM:" && status >> value) return value;
    status.ignore(1 << 12, '\n');
  }
  return 0;
}

struct LatestStatus {
  std::mutex mutex;
  std::condition_variable changed;
  msg::MatcherStatus last;
  std::size_t count = 0;
};

using MatcherLoad = test::ProcessTest;

TEST_F(MatcherLoad, FallingBehindItMatchesTheFreshestScanAndSkipsTheRest) {
  const std::string slow_config = path("slow.yaml");
  std::ofstream(slow_config) << "icp: {iterations: 40}\nnearest_neighbour: {index: brute}\n";

  dds::Participant ground(kDomain, dds::default_profiles_path(), "uavslam_loopback", "test");
  LatestStatus status;
  dds::Reader<msg::MatcherStatusPubSubType> status_reader(
      ground, dds::topic_name("uav1", dds::kMatcherStatusTopic), "status_reader",
      [&](const msg::MatcherStatus& m, const eprosima::fastdds::dds::SampleInfo&) {
        {
          std::lock_guard<std::mutex> lock(status.mutex);
          status.last = m;
          ++status.count;
        }
        status.changed.notify_all();
      });

  process::ChildProcess matcher(
      node_argv("slam_matcher", kDomain, {"--sensor", kScenario, "--slam-config", slow_config}),
      log_path("slam_matcher"));
  ASSERT_TRUE(status_reader.wait_for_matched(1, 30s)) << matcher.log();
  const std::string start_at = shared_start_time();
  process::ChildProcess imu(node_argv("imu_bridge", kDomain, sensor_flags(kScenario, start_at)),
                            log_path("imu_bridge"));
  process::ChildProcess lidar(node_argv("lidar_driver", kDomain, sensor_flags(kScenario, start_at)),
                              log_path("lidar_driver"));
  ASSERT_TRUE(lidar.wait(60s)) << lidar.log();
  ASSERT_EQ(lidar.exit_code(), 0) << lidar.log();

  // A matcher that queued every scan would still be ~700 scans (tens of seconds) behind here.
  {
    std::unique_lock<std::mutex> lock(status.mutex);
    ASSERT_TRUE(
        status.changed.wait_for(lock, 5s, [&] { return status.last.scan_seq() >= kLastScan; }))
        << "last matched scan " << status.last.scan_seq() << " of " << kLastScan << "\n"
        << matcher.log();
  }
  const long peak_kb = peak_rss_kb(matcher.pid());
  EXPECT_EQ(matcher.stop(10s), 0) << matcher.log();

  std::lock_guard<std::mutex> lock(status.mutex);
  const msg::MatcherStatus& last = status.last;
  std::cerr << "received " << last.scans_received() << ", skipped " << last.scans_skipped()
            << ", statuses " << status.count << ", peak RSS " << peak_kb / 1024 << " MB\n";
  EXPECT_GT(last.scans_skipped(), 0u) << "the matcher was meant to fall behind";
  // Every status is a matched scan; the rest of what was received was skipped unprocessed.
  EXPECT_GE(last.scans_received() - last.scans_skipped(), status.count);
  // The map of a 20 s flight and the pipeline need well under this; a scan backlog would not.
  EXPECT_GT(peak_kb, 0);
  EXPECT_LT(peak_kb, 256 * 1024);
}

}  // namespace
}  // namespace uavslam
