// libFuzzer target: the MAVLink frame reader and message decoders (src/drivers/mavlink), and the
// autopilot session fed the same stream (heartbeats, COMMAND_ACKs to its stream requests,
// commands to answer, TIMESYNC). Any byte stream, in any chunking, must give only checksum-valid
// frames and decoded messages, never a crash, undefined behaviour or a read past the input; the
// reader must hold at most one frame.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "drivers/mavlink/AutopilotSession.hpp"
#include "drivers/mavlink/CommonMessages.hpp"
#include "drivers/mavlink/FrameReader.hpp"
#include "drivers/mavlink/Messages.hpp"

namespace {

void decode(const uavslam::mavlink::Frame& frame) {
  using namespace uavslam::mavlink;
  switch (frame.message_id) {
    case kHeartbeat:
      decode_heartbeat(frame.payload);
      break;
    case kSystemTime:
      decode_system_time(frame.payload);
      break;
    case kAttitude:
      decode_attitude(frame.payload);
      break;
    case kAttitudeQuaternion:
      decode_attitude_quaternion(frame.payload);
      break;
    case kLocalPositionNed:
      decode_local_position_ned(frame.payload);
      break;
    case kVisionPositionEstimate:
      decode_vision_position_estimate(frame.payload);
      break;
    case kHighresImu:
      decode_highres_imu(frame.payload);
      break;
    case kTimesync:
      decode_timesync(frame.payload);
      break;
    case kOdometry:
      decode_odometry(frame.payload);
      break;
    case kCommandLong:
      decode_command_long(frame.payload);
      break;
    case kCommandAck:
      decode_command_ack(frame.payload);
      break;
    default:
      // The reader hands on known messages only. Each message CommonMessages defines has a seed in
      // corpus/mavlink, so one added there without its case here fails on the seeds, not by luck.
      std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // The first byte picks the chunk size, as UDP datagrams or serial reads would split the stream.
  const std::size_t chunk = 1 + data[0] % 64;
  uavslam::mavlink::FrameReader reader;
  uavslam::mavlink::AutopilotSession session;
  const auto ignore_imu = [](const uavslam::ImuSample&) {};
  const auto ignore_bytes = [](const std::vector<std::uint8_t>&) {};
  for (std::size_t at = 1; at < size; at += chunk) {
    const std::size_t n = std::min(chunk, size - at);
    const std::vector<std::uint8_t> piece(data + at,
                                          data + at + n);  // exact size: ASan sees overreads
    reader.feed(piece.data(), piece.size(), decode);
    // 0.4 s per chunk: resends, give-ups and reboot gaps happen within a few chunks.
    const double now = 0.4 * static_cast<double>(at / chunk);
    session.receive(piece.data(), piece.size(), now, ignore_imu, ignore_bytes);
    session.tick(now, ignore_bytes);
    session.take_reports();
  }
  return 0;
}
