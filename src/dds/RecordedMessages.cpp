#include "dds/RecordedMessages.hpp"

#include <cstring>
#include <functional>
#include <limits>
#include <map>

#include <fastcdr/exceptions/Exception.h>

namespace uavslam::dds {
namespace {

template <typename PubSubType>
RecordedSample decode_as(const std::uint8_t* data, std::size_t size) {
  PubSubType type;
  const std::string name = type.getName();
  const auto fail = [&](const std::string& why) {
    return MalformedMessage("a " + name + " message of " + std::to_string(size) +
                            " bytes does not decode: " + why);
  };
  if (size > std::numeric_limits<std::uint32_t>::max()) throw fail("too large for CDR");
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(size));
  if (size > 0) std::memcpy(payload.data, data, size);
  payload.length = static_cast<std::uint32_t>(size);
  typename PubSubType::type sample;
  try {
    if (!type.deserialize(&payload, &sample)) throw fail("it ends before its fields do");
  } catch (const eprosima::fastcdr::exception::Exception& e) {
    // read_encapsulation() throws BadParamException for a header that is not CDR's.
    throw fail(std::string("not CDR (") + e.what() + ")");
  } catch (const std::bad_alloc&) {
    throw fail("a length field is impossibly large");
  }
  return sample;
}

using Decoder = std::function<RecordedSample(const std::uint8_t*, std::size_t)>;

const std::map<std::string, Decoder>& decoders() {
  static const std::map<std::string, Decoder> table{
      {schema_name<msg::LaserScanPubSubType>(), decode_as<msg::LaserScanPubSubType>},
      {schema_name<msg::ImuPubSubType>(), decode_as<msg::ImuPubSubType>},
      {schema_name<msg::PoseWithCovarianceStampedPubSubType>(),
       decode_as<msg::PoseWithCovarianceStampedPubSubType>},
      {schema_name<msg::MapPointsPubSubType>(), decode_as<msg::MapPointsPubSubType>},
      {schema_name<msg::MatcherStatusPubSubType>(), decode_as<msg::MatcherStatusPubSubType>},
      {schema_name<msg::OccupancyMapPubSubType>(), decode_as<msg::OccupancyMapPubSubType>},
      {schema_name<msg::TwistWithCovarianceStampedPubSubType>(),
       decode_as<msg::TwistWithCovarianceStampedPubSubType>},
  };
  return table;
}

}  // namespace

bool is_recorded_type(const std::string& schema) {
  return decoders().count(schema) != 0;
}

std::optional<RecordedSample> decode_recorded(const std::string& schema, const std::uint8_t* data,
                                              std::size_t size) {
  const auto decoder = decoders().find(schema);
  if (decoder == decoders().end()) return std::nullopt;
  return decoder->second(data, size);
}

}  // namespace uavslam::dds
