// The session state machine through scripted byte exchanges: what it sends, what a sensor answers.
#include <gtest/gtest.h>

#include "drivers/scip2/Encoding.hpp"
#include "drivers/scip2/ReplyText.hpp"
#include "drivers/scip2/ScanReply.hpp"
#include "drivers/scip2/Session.hpp"

namespace uavslam::drivers::scip2 {
namespace {

constexpr const char* kStream = "ME0000108001000";

std::string pp_reply() {
  return reply_text(
      "PP", "00",
      {info_line("MODL", "UTM-30LX"), info_line("DMIN", "23"), info_line("DMAX", "60000"),
       info_line("ARES", "1440"), info_line("AMIN", "0"), info_line("AMAX", "1080"),
       info_line("AFRT", "540"), info_line("SCAN", "2400")});
}

std::string scan_reply(const std::string& echo, std::uint32_t stamp_ms, bool intensity) {
  ScanData scan;
  scan.timestamp_ms = stamp_ms;
  scan.distances_mm.assign(1081, 2000);
  if (intensity) scan.intensities.assign(1081, 300);
  return reply_text(echo, "99", encode_scan_lines(scan));
}

class Scip2Session : public ::testing::Test {
 protected:
  // Expects the session to have sent exactly `sent`, then answers `reply` at time now_.
  void exchange(const std::string& sent, const std::string& reply) {
    ASSERT_EQ(session.take_output(), sent);
    session.receive(reply, now_);
  }

  // Runs the start-up up to the stream request (the sensor clock reads 1000 ms + 1 ms per trip).
  void start_up() {
    session.start(now_);
    exchange("QT\n", reply_text("QT", "00"));
    exchange("SCIP2.0\n", reply_text("SCIP2.0", "0"));
    exchange("VV\n",
             reply_text("VV", "00", {info_line("SERI", "H0912345"), info_line("FIRM", "1.20")}));
    exchange("PP\n", pp_reply());
    exchange("II\n", reply_text("II", "00", {info_line("STAT", "Stable 000 no error.")}));
    exchange("TM0\n", reply_text("TM0", "00"));
    for (int i = 0; i < 10; ++i) {
      const std::string stamp = encode(1000u + static_cast<unsigned>(i), 4);
      now_ += 0.0005;
      exchange("TM1\n", reply_text("TM1", "00", {stamp + checksum(stamp)}));
      now_ += 0.0005;
    }
    exchange("TM2\n", reply_text("TM2", "00"));
  }

  Session session;
  double now_ = 100.0;
};

TEST_F(Scip2Session, StartsUpAndStreamsDistanceAndIntensity) {
  start_up();
  exchange(std::string(kStream) + "\n", reply_text(kStream, "00"));
  EXPECT_EQ(session.state(), Session::State::Streaming);
  ASSERT_TRUE(session.description());
  EXPECT_EQ(session.description()->beams(), 1081);
  EXPECT_EQ(session.sensor_status(), "Stable 000 no error.");
  EXPECT_TRUE(session.clock().round_trip_seen());

  now_ += 0.030;
  session.receive(scan_reply(kStream, 1100, true), now_);
  const auto scans = session.take_scans();
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_EQ(scans[0].data.distances_mm.size(), 1081u);
  EXPECT_EQ(scans[0].data.intensities.size(), 1081u);
  // The shortest TM trip: sent at 100 s, answered 1000 ms, back at 100.0005 s.
  EXPECT_NEAR(scans[0].host_stamp, 100.10025, 1e-6);
}

TEST_F(Scip2Session, FallsBackToDistancesWhenIntensityIsRefused) {
  start_up();
  exchange(std::string(kStream) + "\n", reply_text(kStream, "0E"));
  exchange("MD0000108001000\n", reply_text("MD0000108001000", "00"));
  EXPECT_EQ(session.state(), Session::State::Streaming);
  session.receive(scan_reply("MD0000108001000", 1100, false), now_);
  const auto scans = session.take_scans();
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_TRUE(scans[0].data.intensities.empty());
}

TEST_F(Scip2Session, CountsDroppedAndDamagedScans) {
  start_up();
  exchange(std::string(kStream) + "\n", reply_text(kStream, "00"));
  session.receive(scan_reply(kStream, 1100, true), now_);
  std::string damaged = scan_reply(kStream, 1125, true);
  damaged[damaged.size() - 10] ^= 0x02;
  session.receive(damaged, now_);
  session.receive(scan_reply(kStream, 1150, true), now_);
  session.receive(scan_reply(kStream, 1225, true), now_);  // 1175 and 1200 never came
  EXPECT_EQ(session.take_scans().size(), 3u);
  EXPECT_EQ(session.counts().damaged_scans, 1u);
  EXPECT_EQ(session.counts().dropped_scans, 3u);
  EXPECT_EQ(session.reader_counts().checksum_errors, 1u);
}

TEST_F(Scip2Session, IgnoresAStreamStillRunningFromBefore) {
  session.start(now_);
  ASSERT_EQ(session.take_output(), "QT\n");
  session.receive(scan_reply(kStream, 5, true) + reply_text("QT", "00"), now_);
  EXPECT_EQ(session.take_output(), "SCIP2.0\n");
  EXPECT_EQ(session.counts().stale_replies, 1u);
}

TEST_F(Scip2Session, FailsOnASensorErrorStatus) {
  start_up();
  exchange(std::string(kStream) + "\n", reply_text(kStream, "00"));
  session.receive(reply_text(kStream, "50"), now_);
  EXPECT_EQ(session.state(), Session::State::Failed);
  EXPECT_EQ(session.counts().sensor_errors, 1u);
  EXPECT_EQ(session.sensor_status(), "error status 50");
}

TEST_F(Scip2Session, FailsWhenTheStreamFallsSilent) {
  start_up();
  exchange(std::string(kStream) + "\n", reply_text(kStream, "00"));
  session.tick(now_ + 0.9);
  EXPECT_EQ(session.state(), Session::State::Streaming);
  session.tick(now_ + 1.1);
  EXPECT_EQ(session.state(), Session::State::Failed);
  EXPECT_NE(session.failure().find("no scan"), std::string::npos);
}

TEST_F(Scip2Session, RetriesThenFailsWhenARequestIsNotAnswered) {
  session.start(now_);
  exchange("QT\n", reply_text("QT", "00"));
  exchange("SCIP2.0\n", reply_text("SCIP2.0", "0"));
  ASSERT_EQ(session.take_output(), "VV\n");
  session.tick(now_ + 1.5);
  EXPECT_EQ(session.take_output(), "VV\n");
  session.tick(now_ + 3.0);
  EXPECT_EQ(session.take_output(), "VV\n");
  session.tick(now_ + 4.5);
  EXPECT_EQ(session.state(), Session::State::Failed);
  EXPECT_EQ(session.failure().rfind("no reply to VV", 0), 0u);
}

}  // namespace
}  // namespace uavslam::drivers::scip2
