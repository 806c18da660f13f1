// The replay clock of CARMEN logs (CarmenTimeline) and the scan stream that applies it.
#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "TempDirTest.hpp"
#include "io/CarmenScanStream.hpp"
#include "io/CarmenTimeline.hpp"
#include "io/FileError.hpp"

namespace uavslam::io {
namespace {

using testing::HasSubstr;

TEST(CarmenTimeline, KeepsIncreasingStampsAsTheyAre) {
  CarmenTimeline timeline;
  EXPECT_EQ(timeline.next(976052857.337284), 976052857.337284);
  EXPECT_EQ(timeline.next(976052857.537284), 976052857.537284);
  EXPECT_EQ(timeline.next(976052858.0), 976052858.0);
  EXPECT_EQ(timeline.adjusted(), 0u);
}

TEST(CarmenTimeline, CreepsForwardWhereTheLogsStampsGoBackOrRepeat) {
  CarmenTimeline timeline;
  const std::vector<double> ipc{100.0, 100.2, 99.9, 100.1, 100.1, 100.3, 100.5};
  std::vector<double> stamps;
  for (double t : ipc) stamps.push_back(timeline.next(t));
  const double step = CarmenTimeline::kStep;
  EXPECT_EQ(stamps[0], 100.0);
  EXPECT_EQ(stamps[1], 100.2);
  EXPECT_DOUBLE_EQ(stamps[2], 100.2 + step);      // backwards: just after the last
  EXPECT_DOUBLE_EQ(stamps[3], 100.2 + 2 * step);  // still behind the timeline
  EXPECT_DOUBLE_EQ(stamps[4], 100.2 + 3 * step);  // a repeat
  EXPECT_EQ(stamps[5], 100.3);                    // the log's own stamp again, once ahead
  EXPECT_EQ(stamps[6], 100.5);
  for (std::size_t i = 1; i < stamps.size(); ++i) EXPECT_GT(stamps[i], stamps[i - 1]) << i;
  EXPECT_EQ(timeline.adjusted(), 3u);
}

class CarmenScanStreamTest : public test::TempDirTest {};

std::string flaser(double x, double theta, double ipc) {
  std::string line = "FLASER 4 1.0 2.0 3.0 81.83";
  for (int i = 0; i < 2; ++i) {
    line += " " + std::to_string(x) + " 0.0 " + std::to_string(theta);
  }
  return line + " " + std::to_string(ipc) + " nohost 0.0\n";
}

TEST_F(CarmenScanStreamTest, StreamsScansInFileOrderOnTheTimelineAndReportsBadLines) {
  const std::string log =
      write("log.clf", "# a comment\n" + flaser(0.0, 0.1, 10.0) +
                           "ODOM 0.1 0 0.1 0.5 0 0 10.05 nohost 0\n" + flaser(0.1, 0.2, 10.1) +
                           "FLASER 4 1.0 2.0\n" + flaser(0.2, 0.3, 9.0) + flaser(0.3, 0.4, 10.4));
  CarmenScanStream stream(log);
  std::vector<TimedCarmenScan> scans;
  std::vector<std::string> problems;
  while (auto scan = stream.next()) {
    scans.push_back(*scan);
    for (const std::string& p : stream.take_new_problems()) problems.push_back(p);
  }
  ASSERT_EQ(scans.size(), 4u);
  EXPECT_EQ(stream.scans(), 4u);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    EXPECT_EQ(scans[i].index, i);
    EXPECT_DOUBLE_EQ(scans[i].scan.laser_pose.theta, 0.1 * static_cast<double>(i + 1));
  }
  EXPECT_EQ(scans[1].stamp, scans[1].scan.ipc_timestamp);
  EXPECT_EQ(scans[2].scan.ipc_timestamp, 9.0);
  EXPECT_DOUBLE_EQ(scans[2].stamp, scans[1].stamp + CarmenTimeline::kStep);
  EXPECT_EQ(scans[3].stamp, scans[3].scan.ipc_timestamp);
  EXPECT_EQ(stream.malformed_lines(), 1u);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_THAT(problems[0], HasSubstr(log + ":5:"));
  EXPECT_TRUE(stream.take_new_problems().empty());  // each description handed out once
}

TEST_F(CarmenScanStreamTest, StopsAfterMaxScans) {
  const std::string log =
      write("log.clf", flaser(0.0, 0.0, 1.0) + flaser(0.0, 0.0, 2.0) + flaser(0.0, 0.0, 3.0));
  CarmenScanStream stream(log, 2);
  EXPECT_TRUE(stream.next());
  EXPECT_TRUE(stream.next());
  EXPECT_FALSE(stream.next());
  EXPECT_EQ(stream.scans(), 2u);
}

TEST_F(CarmenScanStreamTest, AMissingFileIsNamed) {
  const std::string missing = path("no_such.clf");
  try {
    CarmenScanStream stream(missing);
    FAIL() << "no FileError";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr(missing));
  }
}

}  // namespace
}  // namespace uavslam::io
