// libFuzzer target: the MAVLink frame reader and message decoders (src/drivers/mavlink). Any byte
// stream, in any chunking, must give only checksum-valid frames and decoded messages, never a
// crash, undefined behaviour or a read past the input; the reader must hold at most one frame.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

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
    default:
      std::abort();  // the reader hands on known messages only
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // The first byte picks the chunk size, as UDP datagrams or serial reads would split the stream.
  const std::size_t chunk = 1 + data[0] % 64;
  uavslam::mavlink::FrameReader reader;
  for (std::size_t at = 1; at < size; at += chunk) {
    const std::size_t n = std::min(chunk, size - at);
    const std::vector<std::uint8_t> piece(data + at,
                                          data + at + n);  // exact size: ASan sees overreads
    reader.feed(piece.data(), piece.size(), decode);
  }
  return 0;
}
