// The MAVLink wire format against the published specification: the checksum's catalogue value,
// CRC_EXTRA and lengths derived from the common.xml definitions against the published values,
// frames built by hand byte by byte, truncation, v1, signing, garbage, resynchronisation and
// sequence gaps.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drivers/mavlink/CommonMessages.hpp"
#include "drivers/mavlink/Crc.hpp"
#include "drivers/mavlink/FrameReader.hpp"
#include "drivers/mavlink/FrameWriter.hpp"
#include "drivers/mavlink/Messages.hpp"

namespace uavslam::mavlink {
namespace {

using Bytes = std::vector<std::uint8_t>;

std::vector<Frame> read_all(FrameReader& reader, const Bytes& bytes, std::size_t chunk = 0) {
  std::vector<Frame> frames;
  const auto keep = [&frames](const Frame& f) { frames.push_back(f); };
  if (chunk == 0) chunk = bytes.size();
  for (std::size_t at = 0; at < bytes.size(); at += chunk) {
    const std::size_t n = std::min(chunk, bytes.size() - at);
    // A copy of exactly n bytes, so a read past the chunk is caught by ASan.
    const Bytes piece(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                      bytes.begin() + static_cast<std::ptrdiff_t>(at + n));
    reader.feed(piece.data(), piece.size(), keep);
  }
  return frames;
}

void append(Bytes& to, const Bytes& more) {
  to.insert(to.end(), more.begin(), more.end());
}

TEST(MavlinkCrc, MatchesTheCrc16Mcrf4xxCatalogueCheckValue) {
  // CRC-16/MCRF4XX: poly 0x1021 reflected, init 0xFFFF, no final XOR; check("123456789") = 0x6F91.
  EXPECT_EQ(crc_accumulate(std::string("123456789"), kCrcInit), 0x6F91);
}

struct Published {
  MessageId id;
  const char* name;
  int crc_extra;
  std::size_t base_length;
  std::size_t full_length;
};

// MAVLINK_MESSAGE_CRCS of the C library generated from common.xml: {id, crc_extra, min_len,
// max_len}.
TEST(MavlinkDefinitions, DeriveThePublishedCrcExtraAndLengths) {
  const Published published[] = {
      {kHeartbeat, "HEARTBEAT", 50, 9, 9},
      {kSystemTime, "SYSTEM_TIME", 137, 12, 12},
      {kAttitude, "ATTITUDE", 39, 28, 28},
      {kAttitudeQuaternion, "ATTITUDE_QUATERNION", 246, 32, 48},
      {kLocalPositionNed, "LOCAL_POSITION_NED", 185, 28, 28},
      {kCommandLong, "COMMAND_LONG", 152, 33, 33},
      {kCommandAck, "COMMAND_ACK", 143, 3, 10},
      {kVisionPositionEstimate, "VISION_POSITION_ESTIMATE", 158, 32, 117},
      {kHighresImu, "HIGHRES_IMU", 93, 62, 63},
      {kTimesync, "TIMESYNC", 34, 16, 18},
      {kOdometry, "ODOMETRY", 91, 230, 233},
  };
  for (const Published& p : published) {
    const MessageDefinition& d = definition(p.id);
    EXPECT_EQ(d.name(), p.name);
    EXPECT_EQ(d.crc_extra(), p.crc_extra) << p.name;
    EXPECT_EQ(d.base_length(), p.base_length) << p.name;
    EXPECT_EQ(d.full_length(), p.full_length) << p.name;
  }
}

TEST(MavlinkDefinitions, OrderFieldsBySizeKeepingExtensionsLast) {
  const MessageDefinition& heartbeat = definition(kHeartbeat);
  EXPECT_EQ(heartbeat.offset("custom_mode"), 0u);  // uint32 before the uint8 fields
  EXPECT_EQ(heartbeat.offset("type"), 4u);
  EXPECT_EQ(heartbeat.offset("mavlink_version"), 8u);
  const MessageDefinition& odometry = definition(kOdometry);
  EXPECT_EQ(odometry.offset("time_usec"), 0u);
  EXPECT_EQ(odometry.offset("x"), 8u);
  EXPECT_EQ(odometry.offset("frame_id"), 228u);  // the uint8 base fields after all floats
  EXPECT_EQ(odometry.offset("child_frame_id"), 229u);
  EXPECT_EQ(odometry.offset("reset_counter"), 230u);  // extensions: XML order, not re-sorted
  EXPECT_EQ(odometry.offset("quality"), 232u);
  EXPECT_EQ(definition(kHighresImu).offset("fields_updated"), 60u);
  const MessageDefinition& command = definition(kCommandLong);
  EXPECT_EQ(command.offset("param1"), 0u);  // XML order: target_system first, floats first here
  EXPECT_EQ(command.offset("param7"), 24u);
  EXPECT_EQ(command.offset("command"), 28u);
  EXPECT_EQ(command.offset("target_system"), 30u);
  EXPECT_EQ(command.offset("confirmation"), 32u);
  const MessageDefinition& ack = definition(kCommandAck);
  EXPECT_EQ(ack.offset("result"), 2u);
  EXPECT_EQ(ack.offset("progress"), 3u);  // extensions in XML order, the int32 not moved ahead
  EXPECT_EQ(ack.offset("result_param2"), 4u);
  EXPECT_EQ(ack.offset("target_component"), 9u);
}

// HEARTBEAT from a companion computer, MAVLink 2, every byte written out from the spec.
Bytes hand_built_heartbeat(std::uint8_t sequence) {
  Bytes frame = {0xFD, 9,    0,    0,    sequence, 42,   197, 0x00,
                 0x00, 0x00, 0x78, 0x56, 0x34,     0x12,  // custom_mode 0x12345678, little-endian
                 18,   8,    0,    4,    3};  // type, autopilot, base_mode, system_status, version
  std::uint16_t crc = crc_accumulate(frame.data() + 1, frame.size() - 1, kCrcInit);
  crc = crc_accumulate(std::uint8_t{50}, crc);  // HEARTBEAT's CRC_EXTRA
  frame.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  frame.push_back(static_cast<std::uint8_t>(crc >> 8));
  return frame;
}

TEST(MavlinkFrameReader, ReadsAFrameBuiltByHandFromTheSpec) {
  FrameReader reader;
  const std::vector<Frame> frames = read_all(reader, hand_built_heartbeat(7));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].version, 2);
  EXPECT_EQ(frames[0].sequence, 7);
  EXPECT_EQ(frames[0].system_id, 42);
  EXPECT_EQ(frames[0].component_id, 197);
  EXPECT_EQ(frames[0].message_id, static_cast<std::uint32_t>(kHeartbeat));
  const Heartbeat h = decode_heartbeat(frames[0].payload);
  EXPECT_EQ(h.custom_mode, 0x12345678u);
  EXPECT_EQ(h.type, kMavTypeOnboardController);
  EXPECT_EQ(h.autopilot, kMavAutopilotInvalid);
  EXPECT_EQ(h.system_status, kMavStateActive);
  EXPECT_EQ(h.mavlink_version, 3);
}

TEST(MavlinkFrameWriter, WritesTheSameBytesAsTheHandBuiltFrame) {
  FrameWriter writer(42, 197);
  Heartbeat h;
  h.type = kMavTypeOnboardController;
  h.autopilot = kMavAutopilotInvalid;
  h.custom_mode = 0x12345678;
  h.system_status = kMavStateActive;
  EXPECT_EQ(writer.frame(kHeartbeat, encode(h)), hand_built_heartbeat(0));
}

TEST(MavlinkFrames, EveryMessageRoundTrips) {
  FrameWriter writer(1, 1);
  FrameReader reader;
  AttitudeQuaternion aq;
  aq.time_boot_ms = 123456;
  aq.q1 = 0.5f, aq.q2 = -0.5f, aq.q3 = 0.5f, aq.q4 = 0.5f;
  aq.yawspeed = -0.25f;
  HighresImu imu;
  imu.time_usec = 9876543210ull;
  imu.zacc = -9.81f;
  imu.xgyro = 0.125f;
  imu.fields_updated = 0x3F;
  Timesync sync{0, -42, 1, 1};
  Odometry odometry;
  odometry.time_usec = 5;
  odometry.x = 1.5f;
  odometry.pose_covariance[20] = 0.75f;
  odometry.quality = -1;
  Bytes stream;
  append(stream, writer.frame(kAttitudeQuaternion, encode(aq)));
  append(stream, writer.frame(kHighresImu, encode(imu)));
  append(stream, writer.frame(kTimesync, encode(sync)));
  append(stream, writer.frame(kOdometry, encode(odometry)));
  CommandLong command;
  command.target_system = 3;
  command.command = kMavCmdSetMessageInterval;
  command.confirmation = 2;
  command.param2 = 2500.0f;
  command.param7 = -1.0f;
  append(stream, writer.frame(kCommandLong, encode(command)));
  CommandAck ack;
  ack.command = kMavCmdSetMessageInterval;
  ack.result = kMavResultDenied;
  ack.result_param2 = -7;
  ack.target_component = 197;
  append(stream, writer.frame(kCommandAck, encode(ack)));
  const std::vector<Frame> frames = read_all(reader, stream, 7);
  ASSERT_EQ(frames.size(), 6u);
  const AttitudeQuaternion aq2 = decode_attitude_quaternion(frames[0].payload);
  EXPECT_EQ(aq2.time_boot_ms, aq.time_boot_ms);
  EXPECT_EQ(aq2.q2, aq.q2);
  EXPECT_EQ(aq2.yawspeed, aq.yawspeed);
  const HighresImu imu2 = decode_highres_imu(frames[1].payload);
  EXPECT_EQ(imu2.time_usec, imu.time_usec);
  EXPECT_EQ(imu2.zacc, imu.zacc);
  EXPECT_EQ(imu2.xgyro, imu.xgyro);
  EXPECT_EQ(imu2.fields_updated, imu.fields_updated);
  EXPECT_EQ(decode_timesync(frames[2].payload).ts1, -42);
  const Odometry odometry2 = decode_odometry(frames[3].payload);
  EXPECT_EQ(odometry2.x, 1.5f);
  EXPECT_EQ(odometry2.pose_covariance[20], 0.75f);
  EXPECT_EQ(odometry2.quality, -1);
  EXPECT_EQ(odometry2.frame_id, kMavFrameLocalNed);
  const CommandLong command2 = decode_command_long(frames[4].payload);
  EXPECT_EQ(command2.target_system, 3);
  EXPECT_EQ(command2.command, kMavCmdSetMessageInterval);
  EXPECT_EQ(command2.confirmation, 2);
  EXPECT_EQ(command2.param2, 2500.0f);
  EXPECT_EQ(command2.param7, -1.0f);
  const CommandAck ack2 = decode_command_ack(frames[5].payload);
  EXPECT_EQ(ack2.command, kMavCmdSetMessageInterval);
  EXPECT_EQ(ack2.result, kMavResultDenied);
  EXPECT_EQ(ack2.result_param2, -7);
  EXPECT_EQ(ack2.target_component, 197);
  EXPECT_EQ(mav_result_name(kMavResultDenied), "MAV_RESULT_DENIED");
  EXPECT_EQ(reader.counts().frames, 6u);
  EXPECT_EQ(reader.counts().sequence_gaps, 0u);
}

TEST(MavlinkFrames, V2TruncatesTrailingZerosAndTheReaderRestoresThem) {
  FrameWriter writer(1, 1);
  VisionPositionEstimate vpe;
  vpe.usec = 77;
  vpe.yaw = 1.0f;  // the last base field; covariance and reset_counter all zero
  const Bytes frame = writer.frame(kVisionPositionEstimate, encode(vpe));
  EXPECT_EQ(frame[1], 32);  // payload length: the 85 zero extension bytes are not sent
  EXPECT_EQ(frame.size(), kHeaderV2 + 32 + kChecksumBytes);
  Attitude level;  // all zero: one payload byte stays
  EXPECT_EQ(writer.frame(kAttitude, encode(level))[1], 1);

  FrameReader reader;
  const std::vector<Frame> frames = read_all(reader, frame);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].payload.size(), 32u);
  const VisionPositionEstimate decoded = decode_vision_position_estimate(frames[0].payload);
  EXPECT_EQ(decoded.usec, 77u);
  EXPECT_EQ(decoded.yaw, 1.0f);
  EXPECT_EQ(decoded.covariance[20], 0.0f);
  EXPECT_EQ(decoded.reset_counter, 0);
}

TEST(MavlinkFrames, V1CarriesTheBaseFieldsOnly) {
  FrameWriter writer(1, 1, 1);
  AttitudeQuaternion aq;
  aq.q1 = 1.0f;
  aq.repr_offset_q = {1, 2, 3, 4};
  const Bytes frame = writer.frame(kAttitudeQuaternion, encode(aq));
  EXPECT_EQ(frame[0], kStxV1);
  EXPECT_EQ(frame[1], 32);
  EXPECT_EQ(frame.size(), kHeaderV1 + 32 + kChecksumBytes);
  FrameReader reader;
  const std::vector<Frame> frames = read_all(reader, frame);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].version, 1);
  EXPECT_EQ(decode_attitude_quaternion(frames[0].payload).q1, 1.0f);
  EXPECT_EQ(decode_attitude_quaternion(frames[0].payload).repr_offset_q[3], 0.0f);
  EXPECT_EQ(reader.counts().v1_frames, 1u);
  EXPECT_THROW(writer.frame(kOdometry, encode(Odometry{})), std::invalid_argument);
}

TEST(MavlinkFrames, SignedFramesAreAcceptedWithTheirSignatureSkipped) {
  FrameWriter writer(1, 1);
  Signature signature;
  signature.link_id = 3;
  signature.timestamp = 0xFDFDFDFDFDull;  // start markers inside the signature must not matter
  signature.hash = {0xFD, 0xFE, 0xFD, 0xFE, 0xFD, 0xFE};
  Attitude attitude;
  attitude.roll = 0.5f;
  Bytes stream = writer.frame(kAttitude, encode(attitude), signature);
  EXPECT_EQ(stream[2], kIncompatSigned);
  append(stream, writer.frame(kAttitude, encode(attitude)));
  FrameReader reader;
  const std::vector<Frame> frames = read_all(reader, stream);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_TRUE(frames[0].is_signed());
  EXPECT_EQ(decode_attitude(frames[0].payload).roll, 0.5f);
  EXPECT_EQ(reader.counts().signed_frames, 1u);
  EXPECT_EQ(reader.counts().garbage_bytes, 0u);
  EXPECT_EQ(reader.counts().crc_errors, 0u);
}

TEST(MavlinkFrameReader, CountsGarbageAndBadChecksumsAndResynchronises) {
  FrameWriter writer(1, 1);
  Attitude attitude;
  attitude.pitch = 0.25f;
  Bytes stream = {0x00, 0x11, 0x22, 0x33};  // line noise
  append(stream, writer.frame(kAttitude, encode(attitude)));
  Bytes corrupted = writer.frame(kAttitude, encode(attitude));
  corrupted[12] ^= 0x40;  // a payload bit flipped on the way
  append(stream, corrupted);
  stream.push_back(0xFD);  // a lone marker, then a truncated header
  stream.push_back(0x01);
  append(stream, writer.frame(kAttitude, encode(attitude)));
  FrameReader reader;
  const std::vector<Frame> frames = read_all(reader, stream, 1);  // byte by byte, as a UART
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(decode_attitude(frames[1].payload).pitch, 0.25f);
  EXPECT_GE(reader.counts().crc_errors, 1u);
  EXPECT_GE(reader.counts().garbage_bytes, 4u);
  EXPECT_EQ(reader.counts().sequence_gaps, 1u);  // the corrupted frame's sequence number
}

TEST(MavlinkFrameReader, CountsSequenceGapsPerSenderAcrossTheWrap) {
  FrameWriter autopilot(1, 1);
  FrameWriter camera(1, 100);
  Bytes stream;
  for (int i = 0; i < 300; ++i) {  // through 255 -> 0 without a gap
    append(stream, autopilot.frame(kSystemTime, encode(SystemTime{1, 2})));
    if (i % 50 == 0) append(stream, camera.frame(kSystemTime, encode(SystemTime{1, 2})));
  }
  autopilot.skip_sequence(3);
  append(stream, autopilot.frame(kSystemTime, encode(SystemTime{1, 2})));
  FrameReader reader;
  EXPECT_EQ(read_all(reader, stream).size(), 307u);
  EXPECT_EQ(reader.counts().sequence_gaps, 3u);
}

TEST(MavlinkFrameReader, SkipsUnknownMessagesAndUnsupportedFlags) {
  // A frame of SYS_STATUS (id 1), which this driver does not decode: skipped whole, counted.
  Bytes stream = {0xFD, 3, 0, 0, 0, 1, 1, 1, 0, 0, 0xFD, 0xFD, 0xFD, 0x12, 0x34};
  Bytes flagged = FrameWriter(1, 1).frame(kSystemTime, encode(SystemTime{5, 6}));
  flagged[2] = 0x02;  // an incompat flag nobody defined: the frame must be dropped
  std::uint16_t crc = crc_accumulate(flagged.data() + 1, flagged.size() - 3, kCrcInit);
  crc = crc_accumulate(definition(kSystemTime).crc_extra(), crc);
  flagged[flagged.size() - 2] = static_cast<std::uint8_t>(crc & 0xFF);
  flagged[flagged.size() - 1] = static_cast<std::uint8_t>(crc >> 8);
  append(stream, flagged);
  FrameWriter writer(1, 1);
  writer.skip_sequence(1);
  append(stream, writer.frame(kSystemTime, encode(SystemTime{7, 8})));
  FrameReader reader;
  const std::vector<Frame> frames = read_all(reader, stream);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(decode_system_time(frames[0].payload).time_boot_ms, 8u);
  EXPECT_EQ(reader.counts().unknown_messages, 1u);
  EXPECT_EQ(reader.counts().unsupported_flags, 1u);
}

TEST(MavlinkFrameReader, WaitsForTheRestOfASplitFrame) {
  const Bytes frame = hand_built_heartbeat(1);
  FrameReader reader;
  std::size_t seen = 0;
  reader.feed(frame.data(), 5, [&seen](const Frame&) { ++seen; });
  EXPECT_EQ(seen, 0u);
  reader.feed(frame.data() + 5, frame.size() - 5, [&seen](const Frame&) { ++seen; });
  EXPECT_EQ(seen, 1u);
  EXPECT_EQ(reader.counts().garbage_bytes, 0u);
}

}  // namespace
}  // namespace uavslam::mavlink
