// Recordings of the wire types: every type a log holds goes to CDR bytes and back unchanged by its
// schema name; bytes that are cut short or not CDR are reported, never a crash; a recording is
// streamed back decoded, skipping (and counting) what is not ours, up to the damage of a cut file.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "TempDirTest.hpp"
#include "dds/McapChannels.hpp"
#include "dds/RecordedMessageStream.hpp"
#include "dds/RecordedMessages.hpp"
#include "io/FileError.hpp"
#include "io/McapWriter.hpp"

namespace uavslam::dds {
namespace {

using ::testing::HasSubstr;

msg::Header header(std::uint64_t seq) {
  msg::Time stamp;
  stamp.sec(12);
  stamp.nanosec(345000000);
  msg::Header h;
  h.stamp(stamp);
  h.frame_id("laser");
  h.seq(seq);
  h.vehicle_id("uav1");
  return h;
}

msg::LaserScan scan(std::uint64_t seq) {
  msg::LaserScan m;
  m.header(header(seq));
  m.angle_min(-2.356f);
  m.angle_increment(0.00437f);
  m.range_max(30.0f);
  for (int i = 0; i < 1080; ++i) m.ranges().push_back(0.5f + 0.01f * float(i));
  return m;
}

msg::Imu imu(std::uint64_t seq) {
  msg::Imu m;
  m.header(header(seq));
  m.orientation().w(0.5);
  m.orientation().z(0.8660254);
  m.angular_velocity().z(0.25);
  m.linear_acceleration().z(9.81);
  return m;
}

msg::PoseWithCovarianceStamped pose() {
  msg::PoseWithCovarianceStamped m;
  m.header(header(3));
  m.position().x(1.5);
  m.orientation().w(1.0);
  m.quality(1.0f);
  m.scan_seq(77);
  return m;
}

template <typename PubSubType>
void expect_round_trip(const typename PubSubType::type& sample) {
  const std::vector<std::uint8_t> bytes = to_cdr<PubSubType>(sample);
  const std::optional<RecordedSample> decoded = decode_recorded(schema_name<PubSubType>(), bytes);
  ASSERT_TRUE(decoded.has_value()) << schema_name<PubSubType>();
  const auto* back = std::get_if<typename PubSubType::type>(&*decoded);
  ASSERT_NE(back, nullptr) << schema_name<PubSubType>();
  EXPECT_TRUE(*back == sample) << schema_name<PubSubType>();
}

TEST(RecordedMessages, EveryLoggedTypeRoundTripsByItsSchemaName) {
  EXPECT_EQ(schema_name<msg::LaserScanPubSubType>(), "uavslam::msg::LaserScan");
  expect_round_trip<msg::LaserScanPubSubType>(scan(41));
  expect_round_trip<msg::ImuPubSubType>(imu(7));
  expect_round_trip<msg::PoseWithCovarianceStampedPubSubType>(pose());
  msg::MapPoints points;
  points.keyframe_index(4);
  points.points().resize(100);
  expect_round_trip<msg::MapPointsPubSubType>(points);
  msg::MatcherStatus status;
  status.scans_received(10);
  expect_round_trip<msg::MatcherStatusPubSubType>(status);
  msg::OccupancyMap map;
  map.resolution(0.1);
  map.octomap_binary().assign(1000, 0x5A);
  expect_round_trip<msg::OccupancyMapPubSubType>(map);
}

TEST(RecordedMessages, AnUnknownSchemaIsLeftToTheCaller) {
  const std::vector<std::uint8_t> bytes = to_cdr<msg::ImuPubSubType>(imu(1));
  EXPECT_FALSE(decode_recorded("geometry_msgs::msg::Pose", bytes).has_value());
  EXPECT_FALSE(is_recorded_type("geometry_msgs::msg::Pose"));
  EXPECT_TRUE(is_recorded_type("uavslam::msg::Imu"));
}

TEST(RecordedMessages, ATruncatedPayloadIsReportedWithItsType) {
  const std::vector<std::uint8_t> bytes = to_cdr<msg::LaserScanPubSubType>(scan(1));
  for (std::size_t size : {std::size_t{0}, std::size_t{3}, std::size_t{40}, bytes.size() / 2}) {
    try {
      decode_recorded("uavslam::msg::LaserScan", bytes.data(), size);
      ADD_FAILURE() << size << " bytes decoded";
    } catch (const MalformedMessage& e) {
      EXPECT_THAT(e.what(), HasSubstr("uavslam::msg::LaserScan"));
      EXPECT_THAT(e.what(), HasSubstr(std::to_string(size) + " bytes"));
    }
  }
}

TEST(RecordedMessages, GarbageIsReportedNeverACrash) {
  const std::vector<std::uint8_t> not_cdr{0x7F, 0x7F, 0x00, 0x00, 1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_THROW(decode_recorded("uavslam::msg::Imu", not_cdr), MalformedMessage);
  // A CDR header, then a sequence length of 4 billion: refused, not allocated.
  std::vector<std::uint8_t> huge = to_cdr<msg::LaserScanPubSubType>(scan(1));
  huge.resize(64);
  for (std::size_t i = 40; i < 64; ++i) huge[i] = 0xFF;
  EXPECT_THROW(decode_recorded("uavslam::msg::LaserScan", huge), MalformedMessage);
}

class RecordedStream : public test::TempDirTest {
 protected:
  // 20 scans and 100 IMU samples, a foreign channel and one malformed IMU message.
  std::string write_recording(const std::string& name) {
    const std::string file = path(name);
    io::McapWriterOptions options;
    options.chunk_size = 16 * 1024;  // several chunks, so a cut leaves whole ones
    io::McapWriter writer(file, options);
    const auto scans = add_dds_channel(writer, "uav1/scan", "uavslam::msg::LaserScan");
    const auto imus = add_dds_channel(writer, "imu", "uavslam::msg::Imu");
    const auto other = writer.add_channel(writer.add_schema("foo::Bar", "omgidl", "struct Bar {};"),
                                          "scan", "cdr");
    const std::vector<std::uint8_t> junk{1, 2, 3};
    for (std::uint32_t i = 0; i < 100; ++i) {
      const std::vector<std::uint8_t> bytes = to_cdr<msg::ImuPubSubType>(imu(i));
      const std::uint64_t t = 1000000000ull + i * 5000000ull;
      if (i == 50) {
        writer.write(imus, i, t, t, junk.data(), junk.size());
      } else {
        writer.write(imus, i, t, t, bytes.data(), bytes.size());
      }
      if (i % 5 != 0) continue;
      const std::vector<std::uint8_t> s = to_cdr<msg::LaserScanPubSubType>(scan(i / 5));
      writer.write(scans, i / 5, t, t, s.data(), s.size());
      writer.write(other, i / 5, t, t, junk.data(), junk.size());
    }
    writer.close();
    return file;
  }
};

TEST_F(RecordedStream, DecodesTheWantedChannelsAndCountsTheRest) {
  RecordedMessageStream stream(write_recording("log.mcap"), {"uav1/scan", "imu", "scan"});
  EXPECT_EQ(stream.first_log_time(), 1000000000ull);
  std::size_t scans = 0, imus = 0;
  while (std::optional<RecordedMessage> m = stream.next()) {
    scans += std::holds_alternative<msg::LaserScan>(m->sample);
    imus += std::holds_alternative<msg::Imu>(m->sample);
  }
  EXPECT_EQ(scans, 20u);
  EXPECT_EQ(imus, 99u);
  EXPECT_EQ(stream.malformed(), 1u);
  EXPECT_EQ(stream.skipped(), 20u);  // the foreign "scan" channel
  const std::vector<std::string> problems = stream.take_new_problems();
  ASSERT_EQ(problems.size(), 2u);  // the malformed message, the foreign channel once
  EXPECT_TRUE(stream.report().complete);
  EXPECT_EQ(stream.damage(), "");
}

TEST_F(RecordedStream, ACutFileGivesItsWholeMessagesAndSaysWhereItStopped) {
  const std::string whole = write_recording("log.mcap");
  const std::string cut = path("cut.mcap");
  std::filesystem::copy_file(whole, cut);
  std::filesystem::resize_file(cut, std::filesystem::file_size(whole) / 2);
  RecordedMessageStream stream(cut, {"uav1/scan"});
  std::size_t scans = 0;
  while (stream.next()) ++scans;
  EXPECT_GT(scans, 3u);
  EXPECT_LT(scans, 20u);
  EXPECT_FALSE(stream.report().complete);
  EXPECT_THAT(stream.damage(), HasSubstr(cut + ": the log stops at byte"));
}

TEST_F(RecordedStream, AFileThatIsNotMcapIsNamed) {
  const std::string file = write("notes.txt", "not a recording\n");
  try {
    RecordedMessageStream stream(file, {});
    ADD_FAILURE() << "opened";
  } catch (const io::FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr(file));
    EXPECT_THAT(e.what(), HasSubstr("not an MCAP file"));
  }
  EXPECT_THROW(RecordedMessageStream(path("missing.mcap"), {}), io::FileError);
}

}  // namespace
}  // namespace uavslam::dds
