// McapListing (src/io/McapListing): what `recorder --dump` prints of a recording, complete or cut
// short.
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "TempDirTest.hpp"
#include "io/McapListing.hpp"
#include "io/RollingMcapWriter.hpp"

namespace uavslam::io {
namespace {

using ::testing::ContainsRegex;
using ::testing::HasSubstr;

class McapListingTest : public test::TempDirTest {
 protected:
  // 2024-05-01T10:00:00Z plus `ms`.
  static std::uint64_t at_ms(std::uint64_t ms) {
    return 1714557600ull * 1000000000u + ms * 1000000u;
  }

  // imu: 5 messages of 40 bytes 10 ms apart; scan: 2 of 1000 bytes; silent: none.
  std::string flight() {
    RollingMcapOptions o;
    o.sync_on_flush = false;
    RollingMcapWriter writer(path("flight.mcap"), o);
    const std::size_t imu = writer.add_topic("uav1/imu", "uavslam::msg::Imu", "idl imu");
    const std::size_t scan = writer.add_topic("uav1/scan", "uavslam::msg::LaserScan", "idl scan");
    writer.add_topic("uav1/silent", "uavslam::msg::Imu", "idl imu");
    const std::vector<std::uint8_t> small(40, 1), large(1000, 2);
    for (std::uint64_t i = 0; i < 5; ++i) {
      writer.write(imu, at_ms(125 + 10 * i), at_ms(120 + 10 * i), small.data(), small.size());
      if (i % 3 == 0) writer.write(scan, at_ms(130 + i), at_ms(128), large.data(), large.size());
      writer.flush();  // a chunk each, so that a cut file keeps the first ones
    }
    writer.close();
    return path("flight_000.mcap");
  }
};

TEST_F(McapListingTest, ListsEveryChannelWithItsCountsAndTimes) {
  const McapListing listing = list_mcap(flight());
  EXPECT_TRUE(listing.report.complete) << listing.report.problem;
  EXPECT_EQ(listing.messages, 7u);
  ASSERT_EQ(listing.channels.size(), 3u);
  const McapChannelListing& imu = listing.channels[0];
  EXPECT_EQ(imu.topic, "uav1/imu");
  EXPECT_EQ(imu.type, "uavslam::msg::Imu");
  EXPECT_EQ(imu.message_encoding, "cdr");
  EXPECT_EQ(imu.messages, 5u);
  EXPECT_EQ(imu.bytes, 200u);
  EXPECT_EQ(imu.first_log_time, at_ms(125));
  EXPECT_EQ(imu.last_log_time, at_ms(165));
  EXPECT_EQ(messages_on(listing, "uav1/scan"), 2u);
  EXPECT_EQ(messages_on(listing, "uav1/silent"), 0u);
  EXPECT_EQ(messages_on(listing, "nothing"), 0u);

  const std::string text = format_listing(listing);
  EXPECT_THAT(text, HasSubstr(path("flight_000.mcap") + ": 7 messages on 3 channels\n"));
  EXPECT_THAT(text, ContainsRegex("uav1/imu +uavslam::msg::Imu +5 messages +200 bytes +"
                                  "2024-05-01T10:00:00.125Z \\.\\. 2024-05-01T10:00:00.165Z "
                                  "\\(0.040 s\\)"));
  EXPECT_THAT(text, ContainsRegex("uav1/silent +uavslam::msg::Imu +0 messages +0 bytes\n"));
  EXPECT_THAT(text, testing::EndsWith("\ncomplete\n"));
}

TEST_F(McapListingTest, ACutFileListsWhatIsWholeAndSaysWhereItStopped) {
  const std::string file = flight();
  std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
  const McapListing listing = list_mcap(file);
  EXPECT_FALSE(listing.report.complete);
  EXPECT_GT(listing.messages, 0u);
  EXPECT_LT(listing.messages, 7u);
  EXPECT_THAT(format_listing(listing), ContainsRegex("\ndamaged: stopped at byte [0-9]+: .+\n$"));
}

TEST_F(McapListingTest, AFileThatCannotBeOpenedIsAFileError) {
  EXPECT_THROW(list_mcap(path("missing.mcap")), FileError);
}

}  // namespace
}  // namespace uavslam::io
