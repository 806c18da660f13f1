#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/SampleLog.hpp"

namespace uavslam::io {
namespace {

using Bytes = std::vector<std::uint8_t>;
using testing::HasSubstr;

class SampleLogTest : public testing::Test {
 protected:
  ~SampleLogTest() override {
    for (const std::string& path : paths_) std::remove(path.c_str());
  }

  std::string temp_path(const std::string& name) {
    const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
    paths_.push_back(testing::TempDir() + "uavslam_" + test->name() + "_" + name);
    return paths_.back();
  }

  static Bytes bytes_of(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

  static void write_bytes(const std::string& path, const Bytes& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  }

  // A log of two channels and three samples (the last on "scan", 100 bytes of payload).
  std::string three_samples(const std::string& name) {
    const std::string path = temp_path(name);
    SampleLogWriter writer(path);
    const auto scan = writer.add_channel("uav1/scan", "uavslam::msg::LaserScan");
    const auto imu = writer.add_channel("uav1/imu", "uavslam::msg::Imu");
    const Bytes small{1, 2, 3};
    const Bytes large(100, 0xAB);
    writer.write(scan, 1000, 900, small.data(), small.size());
    writer.write(imu, 2000, 1900, small.data(), small.size());
    writer.write(scan, 3000, 2900, large.data(), large.size());
    writer.close();
    return path;
  }

 private:
  std::vector<std::string> paths_;
};

// The layout documented in SampleLog.hpp is a promise to other readers (a later MCAP
// converter, scripts): pin it byte for byte.
TEST_F(SampleLogTest, WritesTheDocumentedLayout) {
  const std::string path = temp_path("layout.uavlog");
  SampleLogWriter writer(path);
  const auto id = writer.add_channel("s", "T");
  const Bytes payload{0xCA, 0xFE};
  writer.write(id, 0x0102030405060708, -1, payload.data(), payload.size());
  writer.close();

  // clang-format off
  const Bytes expected{
      'U', 'A', 'V', 'S', 'L', 'O', 'G', 0,            // magic
      1, 0, 0, 0,                                      // version 1
      1, 8, 0, 0, 0,                                   // channel record, 8 body bytes
      0, 0, 1, 0, 's', 1, 0, 'T',                      // id 0, topic "s", type "T"
      2, 20, 0, 0, 0,                                  // sample record, 18 + 2 body bytes
      0, 0,                                            // channel 0
      8, 7, 6, 5, 4, 3, 2, 1,                          // receive time, little-endian
      0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,  // source time -1
      0xCA, 0xFE};                                     // payload
  // clang-format on
  EXPECT_EQ(bytes_of(path), expected);
  EXPECT_EQ(writer.bytes_written(), expected.size());
}

TEST_F(SampleLogTest, ReadsBackEveryChannelAndSample) {
  const SampleLog log = read_sample_log(three_samples("round.uavlog"));
  ASSERT_EQ(log.channels.size(), 2u);
  EXPECT_EQ(log.channels[0].topic, "uav1/scan");
  EXPECT_EQ(log.channels[0].type, "uavslam::msg::LaserScan");
  EXPECT_EQ(log.channels[1].id, 1);
  EXPECT_EQ(log.channels[1].topic, "uav1/imu");
  ASSERT_EQ(log.samples.size(), 3u);
  EXPECT_EQ(log.samples[1].channel, 1);
  EXPECT_EQ(log.samples[1].receive_time_ns, 2000);
  EXPECT_EQ(log.samples[1].source_time_ns, 1900);
  EXPECT_EQ(log.samples[1].payload, (Bytes{1, 2, 3}));
  EXPECT_EQ(log.samples[2].payload, Bytes(100, 0xAB));
  EXPECT_TRUE(log.damage.empty());
}

TEST_F(SampleLogTest, AnEmptyPayloadAndAHeaderOnlyFileAreValid) {
  const std::string empty = temp_path("empty.uavlog");
  SampleLogWriter(empty).close();
  EXPECT_TRUE(read_sample_log(empty).samples.empty());

  const std::string path = temp_path("zero.uavlog");
  SampleLogWriter writer(path);
  writer.write(writer.add_channel("a", "A"), 5, 6, nullptr, 0);
  writer.close();
  const SampleLog log = read_sample_log(path);
  ASSERT_EQ(log.samples.size(), 1u);
  EXPECT_TRUE(log.samples[0].payload.empty());
}

TEST_F(SampleLogTest, TheSameChannelTwiceKeepsOneId) {
  const std::string path = temp_path("dup.uavlog");
  SampleLogWriter writer(path);
  EXPECT_EQ(writer.add_channel("a", "A"), 0);
  EXPECT_EQ(writer.add_channel("b", "A"), 1);
  EXPECT_EQ(writer.add_channel("a", "A"), 0);
  writer.close();
  EXPECT_EQ(read_sample_log(path).channels.size(), 2u);
}

TEST_F(SampleLogTest, WritingToAnUndeclaredChannelIsRefused) {
  SampleLogWriter writer(temp_path("undeclared.uavlog"));
  const Bytes payload{1};
  EXPECT_THROW(writer.write(0, 0, 0, payload.data(), payload.size()), std::invalid_argument);
}

TEST_F(SampleLogTest, AnUnwritablePathIsAFileErrorNamingIt) {
  const std::string path = testing::TempDir() + "no_such_dir_uavslam/out.uavlog";
  try {
    SampleLogWriter writer(path);
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path));
  }
}

// A recorder killed mid-write: wherever the file ends inside the last record, the first two
// samples come back and the damage names the file and where the last record starts.
TEST_F(SampleLogTest, EveryCompleteRecordBeforeATruncatedTailIsRecovered) {
  const std::string path = three_samples("full.uavlog");
  const Bytes full = bytes_of(path);
  const std::size_t last_record = full.size() - (5 + 18 + 100);
  const std::string cut = temp_path("cut.uavlog");
  for (std::size_t length = last_record + 1; length < full.size(); ++length) {
    write_bytes(cut, Bytes(full.begin(), full.begin() + std::ptrdiff_t(length)));
    const SampleLog log = recover_sample_log(cut);
    ASSERT_EQ(log.samples.size(), 2u) << "cut at " << length;
    EXPECT_EQ(log.samples[1].receive_time_ns, 2000);
    EXPECT_THAT(log.damage,
                HasSubstr(cut + ": byte " + std::to_string(last_record) + ": truncated"))
        << "cut at " << length;
    EXPECT_THROW(read_sample_log(cut), FileError);
  }
  write_bytes(cut, Bytes(full.begin(), full.begin() + std::ptrdiff_t(last_record)));
  EXPECT_TRUE(recover_sample_log(cut).damage.empty()) << "a cut between records is a complete file";
}

TEST_F(SampleLogTest, ANonLogFileIsAFileErrorAtByteZero) {
  const std::string path = temp_path("text.uavlog");
  write_bytes(path, Bytes{'h', 'e', 'l', 'l', 'o', '\n'});
  try {
    read_sample_log(path);
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path + ": byte 0: not a uavslam sample log"));
  }
  EXPECT_THROW(recover_sample_log(path), FileError) << "recovery needs a valid header";
  EXPECT_THROW(read_sample_log(temp_path("missing.uavlog")), FileError);
}

TEST_F(SampleLogTest, AnotherVersionIsRefused) {
  const std::string path = three_samples("v2.uavlog");
  Bytes bytes = bytes_of(path);
  bytes[8] = 2;
  write_bytes(path, bytes);
  try {
    read_sample_log(path);
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unsupported sample log version 2"));
  }
}

TEST_F(SampleLogTest, CorruptRecordsAreNamedByOffset) {
  const std::string path = three_samples("corrupt.uavlog");
  const Bytes good = bytes_of(path);
  const std::size_t first_sample = 12 + (5 + 2 + 2 + 9 + 2 + 23) + (5 + 2 + 2 + 8 + 2 + 17);

  Bytes undeclared = good;
  undeclared[first_sample + 5] = 7;  // channel 7
  write_bytes(path, undeclared);
  EXPECT_THAT(recover_sample_log(path).damage, HasSubstr("byte " + std::to_string(first_sample) +
                                                         ": sample of undeclared channel 7"));

  Bytes zero_kind = good;
  zero_kind[first_sample] = 0;
  write_bytes(path, zero_kind);
  EXPECT_THAT(recover_sample_log(path).damage,
              HasSubstr("byte " + std::to_string(first_sample) + ": corrupt record"));

  Bytes huge = good;
  huge[first_sample + 4] = 0x7F;  // a length near 2 GiB
  write_bytes(path, huge);
  EXPECT_THAT(recover_sample_log(path).damage, HasSubstr("corrupt record"));

  Bytes short_sample = good;
  short_sample[first_sample + 1] = 4;  // 4 body bytes: too short for a sample's fields
  write_bytes(path, Bytes(short_sample.begin(), short_sample.begin() + first_sample + 5 + 4));
  EXPECT_THAT(recover_sample_log(path).damage, HasSubstr("too short"));
}

TEST_F(SampleLogTest, RecordsOfALaterKindAreSkipped) {
  const std::string path = three_samples("later.uavlog");
  Bytes bytes = bytes_of(path);
  const Bytes extra{9, 3, 0, 0, 0, 'x', 'y', 'z'};  // kind 9, 3 body bytes
  bytes.insert(bytes.begin() + 12, extra.begin(), extra.end());
  write_bytes(path, bytes);
  EXPECT_EQ(read_sample_log(path).samples.size(), 3u);
}

TEST_F(SampleLogTest, SummaryCountsSamplesBytesAndTimeSpanPerChannel) {
  const std::vector<ChannelSummary> summary =
      summarize(read_sample_log(three_samples("summary.uavlog")));
  ASSERT_EQ(summary.size(), 2u);
  EXPECT_EQ(summary[0].channel.topic, "uav1/scan");
  EXPECT_EQ(summary[0].samples, 2u);
  EXPECT_EQ(summary[0].payload_bytes, 103u);
  EXPECT_EQ(summary[0].first_receive_ns, 1000);
  EXPECT_EQ(summary[0].last_receive_ns, 3000);
  EXPECT_EQ(summary[1].samples, 1u);
  EXPECT_EQ(summary[1].first_receive_ns, 2000);
  EXPECT_EQ(summary[1].last_receive_ns, 2000);
}

}  // namespace
}  // namespace uavslam::io
