#include "dds/McapChannels.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>

#include "dds/IdlSchemas.hpp"

namespace uavslam::dds {

std::uint16_t add_dds_channel(io::McapWriter& writer, const std::string& topic,
                              const std::string& type_name) {
  const std::optional<std::string> idl = idl_schema(type_name);
  if (!idl) throw std::invalid_argument("no IDL schema for the type " + type_name);
  const std::uint16_t schema = writer.add_schema(type_name, io::kRecordingSchemaEncoding, *idl);
  return writer.add_channel(schema, topic, io::kRecordingMessageEncoding,
                            {{io::kRecordingTypeKey, type_name}});
}

std::uint64_t to_mcap_time(double seconds) {
  if (!(seconds > 0.0)) return 0;
  return static_cast<std::uint64_t>(std::llround(seconds * 1e9));
}

}  // namespace uavslam::dds
