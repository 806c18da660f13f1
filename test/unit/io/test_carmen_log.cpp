#include <sys/stat.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/CarmenLog.hpp"
#include "io/NoReturnCode.hpp"

namespace uavslam::io {
namespace {

using testing::HasSubstr;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

class CarmenLogTest : public testing::Test {
 protected:
  ~CarmenLogTest() override {
    for (const std::string& path : paths_) std::remove(path.c_str());
  }

  std::string write_log(const std::string& text) {
    const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
    paths_.push_back(testing::TempDir() + "uavslam_" + test->name() + ".clf");
    std::ofstream(paths_.back(), std::ios::trunc) << text;
    return paths_.back();
  }

 private:
  std::vector<std::string> paths_;
};

// "FLASER n r... pose odom ipc host logger" with ranges 1, 2, 3, ...
std::string flaser_line(int beams, double ipc_timestamp) {
  std::string line = "FLASER " + std::to_string(beams);
  for (int i = 0; i < beams; ++i) line += " " + std::to_string(i + 1) + ".5";
  line += " 1.0 2.0 0.5 0.9 2.0 0.5 " + std::to_string(ipc_timestamp) + " nohost 0.25\n";
  return line;
}

const CarmenScan& scan_at(const CarmenLog& log, std::size_t i) {
  return std::get<CarmenScan>(log.messages.at(i));
}

TEST_F(CarmenLogTest, Flaser180BeamsStepOneDegreeFromMinus90) {
  const CarmenLog log = read_carmen_log(write_log(flaser_line(180, 10.5)));
  ASSERT_EQ(log.messages.size(), 1u);
  const CarmenScan& scan = scan_at(log, 0);
  EXPECT_EQ(scan.message, CarmenScan::Message::flaser);
  ASSERT_EQ(scan.ranges.size(), 180u);
  EXPECT_FLOAT_EQ(scan.ranges[0], 1.5f);
  EXPECT_FLOAT_EQ(scan.ranges[179], 180.5f);
  EXPECT_NEAR(scan.beam_angle(0), -90 * kDeg, 1e-12);
  EXPECT_NEAR(scan.beam_angle(90), 0.0, 1e-12);
  EXPECT_NEAR(scan.beam_angle(179), 89 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(scan.ipc_timestamp, 10.5);
  EXPECT_DOUBLE_EQ(scan.laser_pose.x, 1.0);
  EXPECT_DOUBLE_EQ(scan.laser_pose.y, 2.0);
  EXPECT_DOUBLE_EQ(scan.laser_pose.theta, 0.5);
  EXPECT_DOUBLE_EQ(scan.robot_pose.x, 0.9);
  EXPECT_DOUBLE_EQ(scan.max_range, kFlaserMaxRange);
  EXPECT_EQ(scan.line, 1u);
  EXPECT_EQ(log.malformed_lines, 0u);
}

TEST_F(CarmenLogTest, Flaser360And361BeamsStepHalfADegree) {
  const CarmenLog log = read_carmen_log(write_log(flaser_line(360, 1) + flaser_line(361, 2)));
  ASSERT_EQ(log.messages.size(), 2u);
  const CarmenScan& half_open = scan_at(log, 0);
  EXPECT_NEAR(half_open.beam_angle(0), -90 * kDeg, 1e-12);
  EXPECT_NEAR(half_open.beam_angle(359), 89.5 * kDeg, 1e-12);
  const CarmenScan& inclusive = scan_at(log, 1);
  EXPECT_NEAR(inclusive.beam_angle(0), -90 * kDeg, 1e-12);
  EXPECT_NEAR(inclusive.beam_angle(180), 0.0, 1e-12);
  EXPECT_NEAR(inclusive.beam_angle(360), 90 * kDeg, 1e-12);
}

TEST_F(CarmenLogTest, OtherFlaserCountsSpan180DegreesInclusively) {
  EXPECT_NEAR(flaser_angle_increment(181), 1 * kDeg, 1e-15);
  EXPECT_NEAR(flaser_angle_increment(91), 2 * kDeg, 1e-15);
}

TEST_F(CarmenLogTest, FlaserNoReturnAtOrAboveTheSickCode) {
  std::string line = "FLASER 180 81.83 81.91 81.82";
  for (int i = 3; i < 180; ++i) line += " 1.0";
  line += " 0 0 0 0 0 0 1.0 nohost 0\n";
  const CarmenLog log = read_carmen_log(write_log(line));
  ASSERT_EQ(log.messages.size(), 1u);
  const CarmenScan& scan = scan_at(log, 0);
  EXPECT_FALSE(scan.is_return(0));
  EXPECT_FALSE(scan.is_return(1));
  EXPECT_TRUE(scan.is_return(2));
  EXPECT_TRUE(scan.is_return(3));
}

TEST_F(CarmenLogTest, RobotLaser1UsesItsOwnAnglesRangeAndLaserPose) {
  const CarmenLog log = read_carmen_log(
      write_log("ROBOTLASER1 0 -1.5 3.0 0.75 30.0 0.01 0 5 1.0 2.0 3.0 4.0 40.0 2 0.1 0.2 "
                "4.0 5.0 0.3 3.9 5.0 0.3 0.2 0.1 0.5 0.6 0.7 123.25 host 0.5\n"));
  ASSERT_EQ(log.messages.size(), 1u) << (log.problems.empty() ? "" : log.problems[0]);
  const CarmenScan& scan = scan_at(log, 0);
  EXPECT_EQ(scan.message, CarmenScan::Message::robotlaser1);
  ASSERT_EQ(scan.ranges.size(), 5u);
  EXPECT_DOUBLE_EQ(scan.beam_angle(0), -1.5);
  EXPECT_DOUBLE_EQ(scan.beam_angle(4), 1.5);
  EXPECT_DOUBLE_EQ(scan.max_range, 30.0);
  EXPECT_TRUE(scan.is_return(3));
  EXPECT_FALSE(scan.is_return(4));
  EXPECT_DOUBLE_EQ(scan.laser_pose.x, 4.0);
  EXPECT_DOUBLE_EQ(scan.laser_pose.theta, 0.3);
  EXPECT_DOUBLE_EQ(scan.robot_pose.x, 3.9);
  EXPECT_DOUBLE_EQ(scan.ipc_timestamp, 123.25);
}

TEST_F(CarmenLogTest, OdomIsReadWithVelocities) {
  const CarmenLog log =
      read_carmen_log(write_log("ODOM 1.5 -2.0 0.25 0.3 -0.1 0.0 976052857.337916 nohost 0.5\n"));
  ASSERT_EQ(log.messages.size(), 1u);
  const auto& odom = std::get<CarmenOdometry>(log.messages[0]);
  EXPECT_DOUBLE_EQ(odom.pose.x, 1.5);
  EXPECT_DOUBLE_EQ(odom.pose.y, -2.0);
  EXPECT_DOUBLE_EQ(odom.pose.theta, 0.25);
  EXPECT_DOUBLE_EQ(odom.tv, 0.3);
  EXPECT_DOUBLE_EQ(odom.rv, -0.1);
  EXPECT_DOUBLE_EQ(odom.ipc_timestamp, 976052857.337916);
}

TEST_F(CarmenLogTest, OtherMessagesCommentsAndBlankLinesAreIgnored) {
  const CarmenLog log = read_carmen_log(
      write_log("# a comment\n\nPARAM robot_length 0.47 1.0 merci 1.0\nSYNC 1 2 3\n"
                "TRUEPOS 0 0 0 0 0 0 1.0 host 1.0\r\n   \nODOM 0 0 0 0 0 0 1.0 nohost 0\r\n"));
  ASSERT_EQ(log.messages.size(), 1u);
  EXPECT_EQ(std::get<CarmenOdometry>(log.messages[0]).line, 7u);
  EXPECT_EQ(log.malformed_lines, 0u);
}

TEST_F(CarmenLogTest, FileOrderIsKeptWhenTimestampsRunBackwards) {
  const CarmenLog log =
      read_carmen_log(write_log("ODOM 0 0 0 0 0 0 5.0 nohost 0\n" + flaser_line(180, 4.0) +
                                "ODOM 1 0 0 0 0 0 3.0 nohost 0\n"));
  ASSERT_EQ(log.messages.size(), 3u);
  EXPECT_DOUBLE_EQ(std::get<CarmenOdometry>(log.messages[0]).ipc_timestamp, 5.0);
  EXPECT_DOUBLE_EQ(scan_at(log, 1).ipc_timestamp, 4.0);
  EXPECT_DOUBLE_EQ(std::get<CarmenOdometry>(log.messages[2]).ipc_timestamp, 3.0);
  EXPECT_EQ(std::get<CarmenOdometry>(log.messages[2]).line, 3u);
}

TEST_F(CarmenLogTest, MalformedLinesAreSkippedCountedAndLocated) {
  std::string short_flaser = flaser_line(180, 2.0);
  short_flaser.replace(0, 10, "FLASER 181");  // one beam more than the line holds
  const std::string path = write_log(
      "ODOM 0 0 0 0 0 0 1.0 nohost 0\n"   // 1 good
      "ODOM 0 0 0 0 0\n"                  // 2 too few fields
      "ODOM 0 x 0 0 0 0 1.0 nohost 0\n"   // 3 not a number
      + short_flaser +                    // 4 beam count does not match
      "FLASER\n"                          // 5 no count at all
      "FLASER -3 1 2 3\n"                 // 6 not a count
      "ROBOTLASER1 0 0 0 0 0 0 0 99 1\n"  // 7 too few fields
      "ODOM 0 0 0 0 0 0 nan nohost 0\n"   // 8 not finite
      + flaser_line(180, 3.0));           // 9 good
  const CarmenLog log = read_carmen_log(path);
  ASSERT_EQ(log.messages.size(), 2u);
  EXPECT_EQ(scan_at(log, 1).line, 9u);
  EXPECT_EQ(log.malformed_lines, 7u);
  ASSERT_EQ(log.problems.size(), 7u);
  EXPECT_THAT(log.problems[0], HasSubstr(path + ":2: ODOM: expected 10 fields, got 6"));
  EXPECT_THAT(log.problems[1], HasSubstr(path + ":3: "));
  EXPECT_THAT(log.problems[1], HasSubstr("'x'"));
  EXPECT_THAT(log.problems[2], HasSubstr(path + ":4: FLASER: beam count 181"));
  EXPECT_THAT(log.problems[3], HasSubstr(path + ":5: "));
  EXPECT_THAT(log.problems[4], HasSubstr(path + ":6: "));
  EXPECT_THAT(log.problems[5], HasSubstr(path + ":7: ROBOTLASER1"));
  EXPECT_THAT(log.problems[6], HasSubstr(path + ":8: "));
}

TEST_F(CarmenLogTest, OnlyTheFirstProblemsAreKeptButAllAreCounted) {
  std::string text;
  for (std::size_t i = 0; i < kMaxReportedProblems + 5; ++i) text += "ODOM 1\n";
  const CarmenLog log = read_carmen_log(write_log(text));
  EXPECT_EQ(log.malformed_lines, kMaxReportedProblems + 5);
  EXPECT_EQ(log.problems.size(), kMaxReportedProblems);
}

TEST_F(CarmenLogTest, MissingFileIsAFileErrorNamingThePath) {
  const std::string path = testing::TempDir() + "uavslam_no_such_log.clf";
  try {
    read_carmen_log(path);
    FAIL() << "no FileError";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path));
  }
}

TEST_F(CarmenLogTest, StreamingReaderGivesTheSameMessages) {
  const std::string path =
      write_log("ODOM 0 0 0 0 0 0 1.0 nohost 0\nbad\nODOM 1\n" + flaser_line(360, 2.0));
  CarmenLogReader reader(path);
  std::vector<CarmenMessage> messages;
  while (auto message = reader.next()) messages.push_back(std::move(*message));
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<CarmenScan>(messages[1]));
  EXPECT_EQ(reader.malformed_lines(), 1u);
}

TEST_F(CarmenLogTest, CoreScanHasThePlanarGeometryAndValidRanges) {
  std::string line = "FLASER 180 81.83";
  for (int i = 1; i < 180; ++i) line += " 2.0";
  line += " 0 0 0 0 0 0 7.5 nohost 0\n";
  const CarmenScan scan = scan_at(read_carmen_log(write_log(line)), 0);
  const auto geometry = std::make_shared<const ScanGeometry>(to_scan_geometry(scan));
  ASSERT_EQ(geometry->directions.size(), 180u);
  EXPECT_NEAR(geometry->directions[0].x(), 0.0, 1e-12);
  EXPECT_NEAR(geometry->directions[0].y(), -1.0, 1e-12);
  EXPECT_NEAR(geometry->directions[90].x(), 1.0, 1e-12);
  EXPECT_TRUE(geometry->mount.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_FALSE(scan.ranges[0] <= geometry->max_range);
  EXPECT_TRUE(scan.ranges[1] <= geometry->max_range);
  const Scan core = to_core_scan(scan, geometry, 4);
  EXPECT_DOUBLE_EQ(core.stamp, 7.5);
  EXPECT_EQ(core.sequence, 4u);
  EXPECT_EQ(core.ranges, scan.ranges);
  EXPECT_EQ(core.geometry, geometry);
}

// FR079's laser sits 0.04 m behind the odometry centre (PARAM robot_frontlaser_offset -0.04): the
// FLASER line's laser pose is the robot pose moved 0.04 m backwards along its heading.
TEST_F(CarmenLogTest, TheLaserMountComesFromTheTwoPosesOfTheMessage) {
  const double heading = 2.797853;
  const double lx = -12.568330 - 0.04 * std::cos(heading);
  const double ly = 10.087026 - 0.04 * std::sin(heading);
  std::string line = "FLASER 180";
  for (int i = 0; i < 180; ++i) line += " 2.0";
  line += " " + std::to_string(lx) + " " + std::to_string(ly) + " 2.797853 -12.568330 10.087026 " +
          "2.797853 7.5 nohost 0\n";
  const CarmenScan scan = scan_at(read_carmen_log(write_log(line)), 0);
  const Eigen::Isometry3d mount = laser_mount(scan);
  EXPECT_DOUBLE_EQ(mount.translation().x(), -0.04);
  EXPECT_DOUBLE_EQ(mount.translation().y(), 0.0);
  EXPECT_TRUE(mount.linear().isApprox(Eigen::Matrix3d::Identity()));
  EXPECT_TRUE(to_scan_geometry(scan).mount.isApprox(mount));
}

// "FLASER 180" with every beam at `range`, except `missing` beams written as `code`.
std::string flaser_with_code(double range, int missing, const std::string& code) {
  std::string line = "FLASER 180";
  for (int i = 0; i < 180; ++i) line += " " + (i < missing ? code : std::to_string(range));
  return line + " 0 0 0 0 0 0 1.0 nohost 0\n";
}

TEST(RangeTally, TheLargestRangeRepeatedFarMoreThanItsNeighboursIsTheCode) {
  RangeTally tally;
  for (int i = 0; i < 30; ++i) tally.add(50.0f);
  for (int i = 0; i < 2; ++i) tally.add(49.8f);
  tally.add(12.5f);
  const std::optional<NoReturnCode> code = tally.no_return_code();
  ASSERT_TRUE(code);
  EXPECT_EQ(code->range, 50.0f);
  EXPECT_EQ(code->readings, 30u);
}

TEST(RangeTally, RealRangesMakeNoCode) {
  RangeTally few;  // the largest range, but seen only a few times: a real far wall
  for (int i = 0; i < 5; ++i) few.add(26.37f);
  few.add(3.0f);
  EXPECT_FALSE(few.no_return_code());
  RangeTally spread;  // repeated, but so are the ranges just below it: a wall at that distance
  for (int i = 0; i < 100; ++i) spread.add(30.0f);
  for (int i = 0; i < 20; ++i) spread.add(29.9f);
  EXPECT_FALSE(spread.no_return_code());
  EXPECT_FALSE(RangeTally().no_return_code());
}

TEST_F(CarmenLogTest, TheReaderLearnsTheLogsNoReturnCode) {
  // A scanner that writes 50.00 for no return (as aces.clf): below the SICK's 81.83 default.
  const std::string with_code =
      flaser_with_code(4.0, 10, "50.00") + flaser_with_code(5.0, 15, "50.00");
  const CarmenLog log = read_carmen_log(write_log(with_code));
  ASSERT_TRUE(log.flaser_no_return);
  EXPECT_EQ(log.flaser_no_return->range, 50.0f);
  EXPECT_EQ(log.flaser_no_return->readings, 25u);
  const CarmenScan& scan = scan_at(log, 0);
  EXPECT_FALSE(scan.is_return(0));
  EXPECT_TRUE(scan.is_return(10));
  EXPECT_FALSE(to_core_scan(scan, std::make_shared<const ScanGeometry>(to_scan_geometry(scan)), 0)
                   .geometry->max_range >= 50.0f);
}

TEST_F(CarmenLogTest, WithoutACodeTheSickDefaultStays) {
  const CarmenLog log = read_carmen_log(write_log(flaser_line(180, 1.0)));
  EXPECT_FALSE(log.flaser_no_return);
  EXPECT_DOUBLE_EQ(scan_at(log, 0).max_range, kFlaserMaxRange);
}

// The real Freiburg benchmark logs, when the shared data folder is present.
std::string freiburg_log(const std::string& name) {
  return std::string(UAVSLAM_SOURCE_DIR) + "/../shared/data/freiburg/" + name;
}

bool exists(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0;
}

struct LogSummary {
  std::size_t flaser = 0;
  std::size_t odom = 0;
  std::set<std::size_t> beam_counts;
  std::size_t scan_stamp_decreases = 0;  // a scan stamped earlier than the scan before it
};

LogSummary summarize(const CarmenLog& log) {
  LogSummary summary;
  double last_scan_stamp = -INFINITY;
  for (const CarmenMessage& message : log.messages) {
    if (const auto* scan = std::get_if<CarmenScan>(&message)) {
      ++summary.flaser;
      summary.beam_counts.insert(scan->ranges.size());
      if (scan->ipc_timestamp < last_scan_stamp) ++summary.scan_stamp_decreases;
      last_scan_stamp = scan->ipc_timestamp;
    } else {
      ++summary.odom;
    }
  }
  return summary;
}

CarmenLog timed_read(const std::string& path) {
  const auto start = std::chrono::steady_clock::now();
  CarmenLog log = read_carmen_log(path);
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  std::cout << "read " << path << ": " << log.messages.size() << " messages in " << took.count()
            << " s\n";
  return log;
}

TEST(CarmenLogFreiburg, IntelLogReadsWholeInFileOrder) {
  const std::string path = freiburg_log("intel.clf");
  if (!exists(path)) GTEST_SKIP() << "Freiburg data absent: " << path << " not found";
  const CarmenLog log = timed_read(path);
  EXPECT_EQ(log.malformed_lines, 0u) << (log.problems.empty() ? "" : log.problems[0]);
  const LogSummary summary = summarize(log);
  EXPECT_EQ(summary.flaser, 13631u);
  EXPECT_EQ(summary.odom, 26915u);
  EXPECT_EQ(summary.beam_counts, std::set<std::size_t>{180});
  EXPECT_EQ(summary.scan_stamp_decreases, 631u);  // file order kept, not sorted by timestamp
}

TEST(CarmenLogFreiburg, Fr079LogReadsWhole) {
  const std::string path = freiburg_log("fr079.clf");
  if (!exists(path)) GTEST_SKIP() << "Freiburg data absent: " << path << " not found";
  const CarmenLog log = timed_read(path);
  EXPECT_EQ(log.malformed_lines, 0u) << (log.problems.empty() ? "" : log.problems[0]);
  const LogSummary summary = summarize(log);
  EXPECT_EQ(summary.flaser, 4934u);
  EXPECT_EQ(summary.odom, 8951u);
  EXPECT_EQ(summary.beam_counts, std::set<std::size_t>{360});
}

// A beam count near SIZE_MAX (found by fuzz_carmen_reader) is no beam count: the no-return pass
// skips the line rather than reading past it, as the reader reports it malformed.
TEST_F(CarmenLogTest, AnImpossibleBeamCountIsSkippedByTheNoReturnPass) {
  std::string text = "FLASER 18446744073709551615 1.5 2.5\n";
  for (int i = 0; i < 30; ++i) text += flaser_line(3, 1.0 + i);
  const std::string path = write_log(text);
  // The 30 good lines alone: their largest range, 3.5, written 30 times and nothing just below.
  const std::optional<NoReturnCode> code = learn_flaser_no_return_code(path);
  ASSERT_TRUE(code);
  EXPECT_EQ(code->range, 3.5f);
  const CarmenLog log = read_carmen_log(path);
  EXPECT_EQ(log.malformed_lines, 1u);
}

// Three scanners, three codes: the SICK's 81.83 and 81.91 (Intel, FR079) and ACES's 50.00.
TEST(CarmenLogFreiburg, EachLogsNoReturnCodeIsLearned) {
  const std::vector<std::pair<std::string, float>> logs = {
      {"intel.clf", 81.83f}, {"fr079.clf", 81.91f}, {"aces.clf", 50.0f}};
  for (const auto& [name, expected] : logs) {
    const std::string path = freiburg_log(name);
    if (!exists(path)) GTEST_SKIP() << "Freiburg data absent: " << path << " not found";
    const std::optional<NoReturnCode> code = learn_flaser_no_return_code(path);
    ASSERT_TRUE(code) << name;
    EXPECT_EQ(code->range, expected) << name;
  }
}

}  // namespace
}  // namespace uavslam::io
