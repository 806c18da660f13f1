// The messages of MAVLink's common.xml (message_definitions/v1.0/common.xml, mavlink.io/en/
// messages/common.html) this driver reads and writes, with their fields as the XML lists them.
// Everything on the wire (field order, offsets, lengths, CRC_EXTRA) is derived from these
// definitions; the unit tests compare the derived CRC_EXTRA with the published values.
#pragma once

#include <cstdint>

#include "drivers/mavlink/MessageDefinition.hpp"

namespace uavslam::mavlink {

enum MessageId : std::uint32_t {
  kHeartbeat = 0,
  kSystemTime = 2,
  kAttitude = 30,
  kAttitudeQuaternion = 31,
  kLocalPositionNed = 32,
  kCommandLong = 76,
  kCommandAck = 77,
  kVisionPositionEstimate = 102,
  kHighresImu = 105,
  kTimesync = 111,
  kOdometry = 331,
};

// The definition of message `id`; nullptr for a message this driver does not know.
const MessageDefinition* find_definition(std::uint32_t id);
// The definition of a message it knows (throws std::out_of_range for another id).
const MessageDefinition& definition(MessageId id);

}  // namespace uavslam::mavlink
