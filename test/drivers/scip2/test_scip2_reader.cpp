// The response framer: any split of the byte stream, garbage and bad checksums counted and
// skipped, a reply cut short followed by the next one, nothing read past the input.
#include <gtest/gtest.h>

#include "drivers/scip2/Encoding.hpp"
#include "drivers/scip2/ReplyText.hpp"
#include "drivers/scip2/ResponseReader.hpp"
#include "drivers/scip2/ScanReply.hpp"

namespace uavslam::drivers::scip2 {
namespace {

std::string scan_reply(std::uint32_t stamp) {
  ScanData scan;
  scan.timestamp_ms = stamp;
  scan.distances_mm.assign(100, 1500);
  return reply_text("MD0000009900000", "99", encode_scan_lines(scan));
}

std::vector<Response> frame(ResponseReader& reader, const std::string& bytes) {
  std::vector<Response> out;
  reader.feed(bytes, out);
  return out;
}

TEST(Scip2ResponseReader, FramesRepliesSplitAnywhere) {
  const std::string stream = reply_text("VV", "00", {info_line("VEND", "Hokuyo")}) +
                             scan_reply(1000) + reply_text("SCIP2.0", "0");
  for (std::size_t chunk = 1; chunk <= 7; ++chunk) {
    ResponseReader reader;
    std::vector<Response> all;
    for (std::size_t at = 0; at < stream.size(); at += chunk) {
      reader.feed(std::string_view(stream).substr(at, chunk), all);
    }
    ASSERT_EQ(all.size(), 3u) << "chunk " << chunk;
    EXPECT_EQ(all[0].echo, "VV");
    EXPECT_EQ(all[0].status, "00");
    EXPECT_EQ(all[0].data, std::vector<std::string>{"VEND:Hokuyo"});
    EXPECT_EQ(all[1].status, "99");
    EXPECT_EQ(all[1].data.size(), 1u + 5u);  // time stamp + 300 characters in 5 lines
    EXPECT_EQ(all[2].echo, "SCIP2.0");
    EXPECT_EQ(all[2].status, "0");
    for (const Response& r : all) EXPECT_TRUE(r.intact);
    EXPECT_EQ(reader.counts().garbage_bytes, 0u);
    EXPECT_EQ(reader.counts().checksum_errors, 0u);
  }
}

TEST(Scip2ResponseReader, SkipsAndCountsGarbageBetweenReplies) {
  ResponseReader reader;
  const std::string garbage = "\x01\xff noise\nxx\n\n";
  const auto out = frame(reader, scan_reply(1) + garbage + scan_reply(2));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(out[1].intact);
  EXPECT_EQ(reader.counts().garbage_bytes, garbage.size());
}

TEST(Scip2ResponseReader, AnEchoLikeGarbageLineIsDroppedWhenNoStatusFollows) {
  ResponseReader reader;
  const auto out = frame(reader, "AB junk\n" + scan_reply(1));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].echo, "MD0000009900000");
  EXPECT_EQ(reader.counts().garbage_bytes, 8u);
}

TEST(Scip2ResponseReader, MarksABadChecksumAndCarriesOn) {
  std::string bad = scan_reply(1);
  bad[bad.find("99b\n") + 9] ^= 0x01;  // a character of the first data block
  ResponseReader reader;
  const auto out = frame(reader, bad + scan_reply(2));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FALSE(out[0].intact);
  EXPECT_TRUE(out[1].intact);
  EXPECT_EQ(reader.counts().checksum_errors, 1u);
}

TEST(Scip2ResponseReader, ResynchronisesAfterAReplyCutShortAtALineEnd) {
  const std::string whole = scan_reply(1);
  std::size_t cut = 0;
  for (int line = 0; line < 4; ++line) cut = whole.find('\n', cut) + 1;  // echo, status, 2 more
  ResponseReader reader;
  const auto out = frame(reader, whole.substr(0, cut) + scan_reply(2) + scan_reply(3));
  ASSERT_EQ(out.size(), 3u);
  EXPECT_FALSE(out[0].intact);
  EXPECT_TRUE(out[1].intact);
  EXPECT_TRUE(out[2].intact);
  EXPECT_EQ(reader.counts().cut_short, 1u);
}

TEST(Scip2ResponseReader, ACutMidLineCostsTheNextReplyToo) {
  const std::string whole = scan_reply(1);
  ResponseReader reader;
  const auto out = frame(reader, whole.substr(0, whole.size() / 2) + scan_reply(2) + scan_reply(3));
  ASSERT_EQ(out.size(), 2u);  // the rest of reply 2 ends the damaged reply 1
  EXPECT_FALSE(out[0].intact);
  EXPECT_TRUE(out[1].intact);
  EXPECT_GE(reader.counts().checksum_errors, 1u);
}

TEST(Scip2ResponseReader, DropsOverlongLines) {
  ResponseReader reader;
  const auto out = frame(reader, std::string(5000, 'A') + "\n" + scan_reply(1));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(reader.counts().garbage_bytes, 5001u);
}

}  // namespace
}  // namespace uavslam::drivers::scip2
