// The recording convention of every MCAP file the project writes (`uavslam simulate --log`, the
// recorder; its constants are io/RollingMcapWriter.hpp's): one Schema per DDS type (its PubSubType
// name, encoding "omgidl", the self-contained IDL text of dds::idl_schema), one Channel per topic
// (the DDS topic name, e.g. "scan" or "uav1/scan"; message_encoding "cdr"; metadata {"dds_type":
// the type name}), and each message the sample's CDR bytes (RecordedMessages.hpp). log_time is the
// receive time (for simulated data the sample's own stamp), publish_time the source's timestamp,
// both ns since the Unix epoch.
#pragma once

#include <cstdint>
#include <string>

#include "io/McapWriter.hpp"
#include "io/RollingMcapWriter.hpp"

namespace uavslam::dds {

// Registers the schema of `type_name` (a PubSubType's getName()) and a channel for `topic`; the
// channel id to write its messages with. std::invalid_argument for a type not in idl/.
std::uint16_t add_dds_channel(io::McapWriter& writer, const std::string& topic,
                              const std::string& type_name);

// Seconds (a stamp) as the ns of an MCAP time; negative stamps are clamped to 0.
std::uint64_t to_mcap_time(double seconds);

}  // namespace uavslam::dds
