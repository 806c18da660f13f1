#include "drivers/mavlink/MessageDefinition.hpp"

#include <algorithm>
#include <stdexcept>

#include "drivers/mavlink/Crc.hpp"

namespace uavslam::mavlink {
namespace {

// mavgen writes the magic version field's type as plain uint8_t into the CRC_EXTRA text.
std::string crc_type_name(const std::string& type) {
  return type == "uint8_t_mavlink_version" ? "uint8_t" : type;
}

std::vector<FieldDefinition> wire_order(std::vector<FieldDefinition> fields) {
  const auto first_extension = std::stable_partition(
      fields.begin(), fields.end(), [](const FieldDefinition& f) { return !f.extension; });
  std::stable_sort(fields.begin(), first_extension,
                   [](const FieldDefinition& a, const FieldDefinition& b) {
                     return type_size(a.type) > type_size(b.type);
                   });
  return fields;
}

}  // namespace

std::size_t type_size(const std::string& type) {
  if (type == "uint64_t" || type == "int64_t" || type == "double") return 8;
  if (type == "uint32_t" || type == "int32_t" || type == "float") return 4;
  if (type == "uint16_t" || type == "int16_t") return 2;
  if (type == "uint8_t" || type == "int8_t" || type == "char" ||
      type == "uint8_t_mavlink_version") {
    return 1;
  }
  throw std::invalid_argument("unknown MAVLink field type '" + type + "'");
}

MessageDefinition::MessageDefinition(std::uint32_t id, std::string name,
                                     std::vector<FieldDefinition> fields)
    : id_(id), name_(std::move(name)) {
  std::uint16_t crc = crc_accumulate(name_ + " ", kCrcInit);
  std::size_t offset = 0;
  for (const FieldDefinition& field : wire_order(std::move(fields))) {
    const std::size_t size = type_size(field.type) * std::max<std::size_t>(field.array_length, 1);
    wire_fields_.push_back({field, offset, size});
    offset += size;
    if (field.extension) continue;
    base_length_ = offset;
    crc = crc_accumulate(crc_type_name(field.type) + " ", crc);
    crc = crc_accumulate(field.name + " ", crc);
    if (field.array_length > 0) {
      crc = crc_accumulate(static_cast<std::uint8_t>(field.array_length), crc);
    }
  }
  full_length_ = offset;
  crc_extra_ = static_cast<std::uint8_t>((crc & 0xFF) ^ (crc >> 8));
}

std::size_t MessageDefinition::offset(const std::string& name) const {
  for (const FieldLayout& layout : wire_fields_) {
    if (layout.field.name == name) return layout.offset;
  }
  throw std::out_of_range("MAVLink message " + name_ + " has no field '" + name + "'");
}

}  // namespace uavslam::mavlink
