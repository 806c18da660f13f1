#include "dds/IdlSchemas.hpp"

#include <regex>

namespace uavslam::dds {

std::optional<std::string> idl_schema(const std::string& type_name) {
  const std::string prefix = "uavslam::msg::";
  if (type_name.rfind(prefix, 0) != 0) return std::nullopt;
  const std::regex defines("\\bstruct\\s+" + type_name.substr(prefix.size()) + "\\s*\\{");
  // A file defines its own type last; Common.idl's types are inlined in the others, so the
  // smallest text defining the name is the type's own file.
  const IdlFile* best = nullptr;
  for (const IdlFile& file : idl_files()) {
    if (!std::regex_search(file.text, defines)) continue;
    if (!best || file.text.size() < best->text.size()) best = &file;
  }
  if (!best) return std::nullopt;
  return best->text;
}

}  // namespace uavslam::dds
