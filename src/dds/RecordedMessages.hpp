// The messages of a recording (an MCAP channel with message_encoding "cdr") as the wire types of
// idl/. A logged message is the sample's CDR bytes exactly as its PubSubType's serialize() writes
// them for DDS (encapsulation header included), so a replay publishes what was received, and any
// CDR reader given the channel's schema (the IDL text, dds::idl_schema) can decode the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <msg/ImuPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/MapPointsPubSubTypes.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/OccupancyMapPubSubTypes.h>
#include <msg/PosePubSubTypes.h>
#include <msg/TwistPubSubTypes.h>

#include "dds/DdsError.hpp"

namespace uavslam::dds {

// A logged message whose bytes are not a sample of its schema's type; the message says why.
class MalformedMessage : public std::runtime_error {
 public:
  explicit MalformedMessage(const std::string& what) : std::runtime_error(what) {}
};

// A sample of any wire type a recording can hold.
using RecordedSample =
    std::variant<msg::LaserScan, msg::Imu, msg::PoseWithCovarianceStamped, msg::MapPoints,
                 msg::MatcherStatus, msg::OccupancyMap, msg::TwistWithCovarianceStamped>;

// The schema name of a wire type in a recording: what its PubSubType's getName() reports, e.g.
// "uavslam::msg::LaserScan".
template <typename PubSubType>
std::string schema_name() {
  PubSubType type;
  return type.getName();
}

// The sample's CDR bytes as serialize() writes them. DdsError when it cannot be serialised.
template <typename PubSubType>
std::vector<std::uint8_t> to_cdr(const typename PubSubType::type& sample) {
  PubSubType type;
  void* data = const_cast<typename PubSubType::type*>(&sample);  // serialize() only reads it
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(data)());
  if (!type.serialize(data, &payload)) {
    throw DdsError("cannot serialise a " + std::string(type.getName()) + " sample");
  }
  return {payload.data, payload.data + payload.length};
}

// True when `schema` names a wire type decode_recorded() knows.
bool is_recorded_type(const std::string& schema);

// Decodes `size` bytes as the wire type named `schema`. nullopt when the schema is not one of
// ours (the caller skips the message and counts it); MalformedMessage naming the type and the
// fault when the bytes are not such a sample (cut short, not CDR). Never allocates more than a
// few times `size`: every sequence length is checked against the bytes that are there.
std::optional<RecordedSample> decode_recorded(const std::string& schema, const std::uint8_t* data,
                                              std::size_t size);

inline std::optional<RecordedSample> decode_recorded(const std::string& schema,
                                                     const std::vector<std::uint8_t>& bytes) {
  return decode_recorded(schema, bytes.data(), bytes.size());
}

}  // namespace uavslam::dds
