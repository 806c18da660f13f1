// Replaying CARMEN logs over DDS: lidar_driver and imu_bridge with --source carmen:FILE on one
// --start-at timeline, into the slam_matcher (--geometry-from-scan) and the recorder, as separate
// OS processes on their own domains (191, 192; with the odometry prior over `odom`: 112, 111; with
// the back end, a map server and a ground station: 109), the test as a ground-side subscriber of
// `pose` and `matcher_status`.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/PosePubSubTypes.h>

#include "BackEndCorrections.hpp"
#include "MatcherListener.hpp"
#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "io/McapListing.hpp"

namespace uavslam {
namespace {

using test::MatcherCounts;
using test::MatcherListener;

using namespace std::chrono_literals;
using ::testing::HasSubstr;

constexpr int kDomain = 191;               // the synthetic log's
constexpr int kIntelDomain = 192;          // intel.clf's
constexpr int kOdometryDomain = 112;       // the synthetic log's, with the odometry prior
constexpr int kIntelOdometryDomain = 111;  // intel.clf's, with the odometry prior
constexpr int kIntelLoopsDomain = 109;     // intel.clf's, with the back end and the map's processes
constexpr double kPi = 3.14159265358979323846;

// A 12 x 8 m room with a pillar and a crate; the robot drives 5 m east while turning 0.3 rad.
struct Box2 {
  double x0, y0, x1, y1;
};
constexpr Box2 kRoom{0.0, 0.0, 12.0, 8.0};
const std::vector<Box2> kObstacles{{5.0, 5.0, 5.6, 5.6}, {9.0, 1.0, 10.0, 2.0}};

// Distance along (dx, dy) from (x, y) to the box's boundary: `inside` for the room's walls.
double ray_to_box(double x, double y, double dx, double dy, const Box2& b, bool inside) {
  const double inf = std::numeric_limits<double>::infinity();
  const auto slab = [&](double p, double d, double lo, double hi, double& near, double& far) {
    if (std::abs(d) < 1e-12) {
      if (p < lo || p > hi) near = inf;
      return;
    }
    const double t0 = (lo - p) / d, t1 = (hi - p) / d;
    near = std::max(near, std::min(t0, t1));
    far = std::min(far, std::max(t0, t1));
  };
  double near = -inf, far = inf;
  slab(x, dx, b.x0, b.x1, near, far);
  slab(y, dy, b.y0, b.y1, near, far);
  if (inside) return far;
  return near <= far && near > 0.0 ? near : inf;
}

double range_at(double x, double y, double angle) {
  const double dx = std::cos(angle), dy = std::sin(angle);
  double range = ray_to_box(x, y, dx, dy, kRoom, true);
  for (const Box2& b : kObstacles) range = std::min(range, ray_to_box(x, y, dx, dy, b, false));
  return range;
}

struct OdometryPose {
  double x, y, theta, stamp;
};

// A FLASER line: 180 beams from -90 deg in 1 deg steps, laser pose = odometry pose.
std::string flaser_line(const OdometryPose& p) {
  std::ostringstream line;
  line.setf(std::ios::fixed);
  line.precision(3);
  line << "FLASER 180";
  for (int i = 0; i < 180; ++i) line << ' ' << range_at(p.x, p.y, p.theta + (i - 90) * kPi / 180);
  line.precision(6);
  for (int twice = 0; twice < 2; ++twice) line << ' ' << p.x << ' ' << p.y << ' ' << p.theta;
  line << ' ' << p.stamp << " nohost " << p.stamp << '\n';
  return line.str();
}

struct SyntheticLog {
  std::vector<OdometryPose> path;
  std::size_t malformed_line = 0;  // 1-based
};

// `scans` FLASER lines at 5 Hz with an ODOM line before each, one malformed line after the tenth.
SyntheticLog write_synthetic_log(const std::string& file, int scans) {
  SyntheticLog log;
  std::ofstream out(file);
  out << "# synthetic CARMEN log: a room, 5 m east\n";
  std::size_t line = 1;
  for (int i = 0; i < scans; ++i) {
    const double s = static_cast<double>(i) / (scans - 1);
    const OdometryPose p{2.0 + 5.0 * s, 3.0 + 0.5 * s * s, 0.3 * s, 1000.0 + 0.2 * i};
    out << "ODOM " << p.x << ' ' << p.y << ' ' << p.theta << " 0.5 0 0 " << p.stamp - 0.01
        << " nohost 0\n";
    out << flaser_line(p);
    line += 2;
    log.path.push_back(p);
    if (i == 9) {
      out << "FLASER 180 1.0 2.0 not_a_number\n";
      log.malformed_line = ++line;
    }
  }
  return log;
}

// The slam_matcher's parameters for 2D logs over DDS: config/slam_2d_logs.yaml without its
// odometry prior (odometry is not on the wire), so the seed's 30 iterations and 0.3 m gate.
std::string write_matcher_config(const std::string& file) {
  std::ofstream(file) << "scan:\n  subsample_every: 1\n"
                         "icp:\n  iterations: 30\n  max_correspondence_distance: 0.3\n"
                         "map:\n  subsample_every: 1\n";
  return file;
}

// The shipped config for 2D logs: the odometry as the motion prior, yaw in every scan,
// point-to-line.
const std::string kLogsConfig = std::string(UAVSLAM_SOURCE_DIR) + "/config/slam_2d_logs.yaml";

// The matcher's summary line of its odometry prior: how many scans were matched with it, without.
struct PriorCounts {
  std::uint64_t received = 0, with_prior = 0, without_prior = 0;
};
std::optional<PriorCounts> prior_counts(const std::string& matcher_log) {
  static const std::regex line(
      R"(odometry prior: (\d+) odometry samples received, \d+ dropped[^,]*, (\d+) scans matched )"
      R"(with the prior, (\d+) without)");
  std::smatch m;
  if (!std::regex_search(matcher_log, m, line)) return std::nullopt;
  return PriorCounts{std::stoull(m[1]), std::stoull(m[2]), std::stoull(m[3])};
}

// The odometry pose of the scan stamped `stamp` (the log's stamps increase: timeline = log).
const OdometryPose& odometry_at(const std::vector<OdometryPose>& path, double stamp) {
  return *std::min_element(path.begin(), path.end(), [&](const auto& a, const auto& b) {
    return std::abs(a.stamp - stamp) < std::abs(b.stamp - stamp);
  });
}

// The scans in a recorder's file, which it closed (summary, Footer) when it stopped.
std::uint64_t scans_recorded(const std::string& file) {
  const io::McapListing listing = io::list_mcap(file);
  EXPECT_TRUE(listing.report.complete) << file << ": " << listing.report.problem;
  return io::messages_on(listing, "uav1/scan");
}

class CarmenReplay : public test::ProcessTest {
 protected:
  std::vector<std::string> node(const char* name, int domain, std::vector<std::string> extra) {
    extra.insert(extra.begin(), {"--vehicle", "uav1"});
    return node_argv(name, domain, extra);
  }

  std::vector<std::string> sensor(const char* name, int domain, const std::string& log,
                                  const std::string& rate, const std::string& start_at,
                                  int subscribers, std::vector<std::string> extra = {}) {
    std::vector<std::string> flags{"--source",
                                   "carmen:" + log,
                                   "--rate",
                                   rate,
                                   "--start-at",
                                   start_at,
                                   "--wait-for-subscribers",
                                   std::to_string(subscribers)};
    flags.insert(flags.end(), extra.begin(), extra.end());
    return node(name, domain, flags);
  }

  // slam_config: empty for the seed's mode (write_matcher_config).
  std::vector<std::string> matcher(int domain, const std::string& initial_position,
                                   const std::string& slam_config = "") {
    return node("slam_matcher", domain,
                {"--geometry-from-scan", "--initial-position", initial_position, "--slam-config",
                 slam_config.empty() ? write_matcher_config(path("slam.yaml")) : slam_config});
  }

  struct IntelRun {
    MatcherCounts counts;
    std::string lidar_log;
    std::string matcher_log;
  };

  // The first `scans` scans of intel.clf at 10x through a matcher with slam_config, to the end
  // (every sensor exits 0, the matcher saw the last scan and stops cleanly).
  IntelRun replay_intel(const std::string& intel, int domain, int scans,
                        std::chrono::seconds timeout, const std::string& slam_config = "") {
    MatcherListener listener(domain, "uav1");
    process::ChildProcess slam(matcher(domain, "0,0,0", slam_config), log_path("slam_matcher"));
    EXPECT_TRUE(listener.matched()) << slam.log();
    const std::string start_at = shared_start_time();
    const std::vector<std::string> first{"--max-scans", std::to_string(scans)};
    process::ChildProcess imu(sensor("imu_bridge", domain, intel, "10", start_at, 1, first),
                              log_path("imu_bridge"));
    process::ChildProcess lidar(sensor("lidar_driver", domain, intel, "10", start_at, 1, first),
                                log_path("lidar_driver"));
    EXPECT_TRUE(lidar.wait(timeout)) << lidar.log();
    EXPECT_EQ(lidar.exit_code(), 0) << lidar.log();
    EXPECT_TRUE(imu.wait(timeout)) << imu.log();
    EXPECT_EQ(imu.exit_code(), 0) << imu.log();
    EXPECT_TRUE(listener.wait_for_scan(std::uint64_t(scans - 1), 10s)) << slam.log();
    EXPECT_EQ(slam.stop(10s), 0) << slam.log();
    std::cerr << lidar.log() << imu.log() << slam.log();
    return {listener.counts(), lidar.log(), slam.log()};
  }
};

TEST_F(CarmenReplay, ASyntheticLogReachesTheMatcherAndTheRecorderScanForScan) {
  constexpr int kScans = 40;
  const std::string log_file = path("room.clf");
  const SyntheticLog log = write_synthetic_log(log_file, kScans);
  const std::string recording = path("replay.mcap");

  MatcherListener listener(kDomain, "uav1");
  process::ChildProcess slam(matcher(kDomain, "2,3,0"), log_path("slam_matcher"));
  process::ChildProcess recorder(node("recorder", kDomain, {"--out", recording}),
                                 log_path("recorder"));
  ASSERT_TRUE(listener.matched()) << slam.log();

  const std::string start_at = shared_start_time();
  process::ChildProcess imu(sensor("imu_bridge", kDomain, log_file, "10", start_at, 2),
                            log_path("imu_bridge"));
  process::ChildProcess lidar(sensor("lidar_driver", kDomain, log_file, "10", start_at, 2),
                              log_path("lidar_driver"));
  ASSERT_TRUE(lidar.wait(60s)) << lidar.log();
  EXPECT_EQ(lidar.exit_code(), 0) << lidar.log();
  ASSERT_TRUE(imu.wait(60s)) << imu.log();
  EXPECT_EQ(imu.exit_code(), 0) << imu.log();
  EXPECT_TRUE(listener.wait_for_scan(kScans - 1, 10s)) << slam.log();
  EXPECT_EQ(slam.stop(10s), 0) << slam.log();
  EXPECT_EQ(recorder.stop(10s), 0) << recorder.log();
  std::cerr << lidar.log() << imu.log() << slam.log() << recorder.log();

  const std::string bad_line = log_file + ":" + std::to_string(log.malformed_line) + ":";
  EXPECT_THAT(lidar.log(), HasSubstr("skipped " + bad_line));
  EXPECT_THAT(lidar.log(),
              HasSubstr("published 40 scans of " + log_file + ", 1 malformed lines skipped"));
  EXPECT_THAT(imu.log(), HasSubstr("published 40 odometry headings"));
  EXPECT_THAT(slam.log(), HasSubstr("slam_matcher: 40 scans received"));
  EXPECT_THAT(recorder.log(), HasSubstr("uav1/scan: 40 received, 40 written, 0 dropped"));
  EXPECT_EQ(scans_recorded(path("replay_000.mcap")), 40u);

  // Most scans matched: a matcher that falls behind skips scans (ScanQueue), but not here.
  const MatcherCounts counts = listener.counts();
  EXPECT_GE(counts.processed(), 30u) << slam.log();
  EXPECT_GE(counts.accepted, counts.processed() * 9 / 10) << slam.log();
  const std::vector<Pose> poses = listener.poses();
  ASSERT_FALSE(poses.empty()) << slam.log();
  const Pose& last = poses.back();
  const OdometryPose& odometry = odometry_at(log.path, last.stamp);
  EXPECT_NEAR(last.stamp, log.path.back().stamp, 0.5) << "the last pose is of the last scans";
  EXPECT_LT(std::hypot(last.position.x() - odometry.x, last.position.y() - odometry.y), 0.05)
      << last.position.transpose() << " at " << last.stamp;
}

TEST_F(CarmenReplay, TheFirst300ScansOfIntelAreMatched) {
  const std::string intel = std::string(UAVSLAM_SOURCE_DIR) + "/../shared/data/freiburg/intel.clf";
  if (!std::filesystem::exists(intel)) GTEST_SKIP() << intel << " is not there (../shared/data)";
  const IntelRun run = replay_intel(intel, kIntelDomain, 300, 120s);
  ASSERT_FALSE(HasFailure());

  EXPECT_THAT(run.lidar_log, HasSubstr("published 300 scans"));
  EXPECT_EQ(run.counts.received, 300u) << run.matcher_log;
  EXPECT_GE(run.counts.processed(), 150u) << run.matcher_log;
  EXPECT_GE(run.counts.accepted, run.counts.processed() * 9 / 10) << run.matcher_log;
}

TEST_F(CarmenReplay, TheOdometryOnTheWireIsTheMatchersMotionPrior) {
  constexpr int kScans = 40;
  const std::string log_file = path("room.clf");
  const SyntheticLog log = write_synthetic_log(log_file, kScans);

  MatcherListener listener(kOdometryDomain, "uav1");
  process::ChildProcess slam(matcher(kOdometryDomain, "2,3,0", kLogsConfig),
                             log_path("slam_matcher"));
  ASSERT_TRUE(listener.matched()) << slam.log();

  const std::string start_at = shared_start_time();
  process::ChildProcess imu(sensor("imu_bridge", kOdometryDomain, log_file, "10", start_at, 1),
                            log_path("imu_bridge"));
  process::ChildProcess lidar(sensor("lidar_driver", kOdometryDomain, log_file, "10", start_at, 1),
                              log_path("lidar_driver"));
  ASSERT_TRUE(lidar.wait(60s)) << lidar.log();
  EXPECT_EQ(lidar.exit_code(), 0) << lidar.log();
  ASSERT_TRUE(imu.wait(60s)) << imu.log();
  EXPECT_EQ(imu.exit_code(), 0) << imu.log();
  EXPECT_TRUE(listener.wait_for_scan(kScans - 1, 10s)) << slam.log();
  EXPECT_EQ(slam.stop(10s), 0) << slam.log();
  std::cerr << imu.log() << slam.log();

  EXPECT_THAT(imu.log(), HasSubstr("published 40 odometry headings and 40 odometry poses"));
  const std::optional<PriorCounts> prior = prior_counts(slam.log());
  ASSERT_TRUE(prior) << slam.log();
  EXPECT_EQ(prior->received, 40u) << slam.log();
  const MatcherCounts counts = listener.counts();
  EXPECT_GE(counts.processed(), 30u) << slam.log();
  EXPECT_EQ(prior->with_prior + prior->without_prior, counts.processed()) << slam.log();
  // Only the first scan (it seeds the map; no scan before it got a pose) goes without.
  EXPECT_EQ(prior->without_prior, 1u) << slam.log();
  EXPECT_GE(counts.accepted, counts.processed() * 9 / 10) << slam.log();
  const std::vector<Pose> poses = listener.poses();
  ASSERT_FALSE(poses.empty()) << slam.log();
  const Pose& last = poses.back();
  const OdometryPose& odometry = odometry_at(log.path, last.stamp);
  EXPECT_NEAR(last.stamp, log.path.back().stamp, 0.5) << "the last pose is of the last scans";
  EXPECT_LT(std::hypot(last.position.x() - odometry.x, last.position.y() - odometry.y), 0.05)
      << last.position.transpose() << " at " << last.stamp;
}

TEST_F(CarmenReplay, TheFirst1000ScansOfIntelAreMatchedWithTheOdometryPrior) {
  const std::string intel = std::string(UAVSLAM_SOURCE_DIR) + "/../shared/data/freiburg/intel.clf";
  if (!std::filesystem::exists(intel)) GTEST_SKIP() << intel << " is not there (../shared/data)";
  // ~200 s of the log in ~20 s: the bursts of its stamps (scans < 20 ms apart) stay within what
  // the matcher (~0.5 ms a scan) takes on a loaded 2-core machine.
  const IntelRun run = replay_intel(intel, kIntelOdometryDomain, 1000, 180s, kLogsConfig);
  ASSERT_FALSE(HasFailure());

  EXPECT_THAT(run.lidar_log, HasSubstr("published 1000 scans"));
  EXPECT_EQ(run.counts.received, 1000u) << run.matcher_log;
  EXPECT_GE(run.counts.processed(), 500u) << run.matcher_log;
  EXPECT_GE(run.counts.accepted, run.counts.processed() * 9 / 10) << run.matcher_log;
  const std::optional<PriorCounts> prior = prior_counts(run.matcher_log);
  ASSERT_TRUE(prior) << run.matcher_log;
  EXPECT_EQ(prior->received, 1000u) << run.matcher_log;
  EXPECT_GE(prior->with_prior, run.counts.processed() * 9 / 10) << run.matcher_log;
}

// The first 2681 scans of intel.clf (about 540 s, with its first loops) replayed over DDS into the
// matcher with the shipped config for 2D logs, whose back end runs on its own thread, beside a
// map server and a ground station: the matcher closes a loop and publishes the correction
// (`keyframe_poses`), the map server moves its keyframes and rebuilds its map, and the ground
// station writes where the graph now puts them.
TEST_F(CarmenReplay, IntelsFirstLoopIsClosedOverDdsAndTheMapFollowsIt) {
  const std::string intel = std::string(UAVSLAM_SOURCE_DIR) + "/../shared/data/freiburg/intel.clf";
  if (!std::filesystem::exists(intel)) GTEST_SKIP() << intel << " is not there (../shared/data)";
  process::ChildProcess map_server(
      node("map_server", kIntelLoopsDomain, {"--publish-period", "0.5"}), log_path("map_server"));
  const std::string station_out = path("ground_station");
  process::ChildProcess station(
      node("ground_station", kIntelLoopsDomain, {"--quiet", "--out", station_out}),
      log_path("ground_station"));
  const IntelRun run = replay_intel(intel, kIntelLoopsDomain, 2681, 240s, kLogsConfig);
  EXPECT_EQ(map_server.stop(10s), 0) << map_server.log();
  EXPECT_EQ(station.stop(20s), 0) << station.log();
  ASSERT_FALSE(HasFailure());
  std::cerr << map_server.log() << station.log();

  const std::optional<test::FollowedCorrections> followed =
      test::expect_corrections_followed(run.matcher_log, map_server.log(), station_out);
  ASSERT_TRUE(followed) << station.log();
  EXPECT_GT(followed->keyframes, 50u);
}

}  // namespace
}  // namespace uavslam
