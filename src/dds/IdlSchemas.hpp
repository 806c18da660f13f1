// The wire types' IDL as text, for the schemas of recordings: an MCAP channel of CDR messages
// carries its type's IDL (schema encoding "omgidl") so Foxglove and other readers can decode it
// with nothing but the file. Embedded at build time from idl/ (idl/embed_schemas.cmake), with the
// includes inlined.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace uavslam::dds {

struct IdlFile {
  std::string name;  // the file's stem, e.g. "LaserScan"
  std::string text;  // self-contained IDL
};

const std::vector<IdlFile>& idl_files();

// The IDL text that defines a fully qualified type, e.g. "uavslam::msg::LaserScan" (the name a
// fastddsgen PubSubType reports); nullopt for a type not in idl/.
std::optional<std::string> idl_schema(const std::string& type_name);

}  // namespace uavslam::dds
