// A MAVLink message as common.xml defines it: its id, name and fields in XML order, and what the
// wire format derives from them (mavlink.io/en/guide/serialization.html): the payload field order
// (base fields sorted by element size, largest first, stable; extension fields after them in XML
// order, never reordered), each field's offset, the base and full payload lengths, and CRC_EXTRA
// (a CRC over the name and the base fields' types, names and array lengths, folded to a byte).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace uavslam::mavlink {

struct FieldDefinition {
  std::string type;  // as in the XML: "uint8_t", "float", "uint8_t_mavlink_version", ...
  std::string name;
  std::size_t array_length = 0;  // 0: not an array
  bool extension = false;        // after <extensions/>: MAVLink 2 only, not in CRC_EXTRA
};

struct FieldLayout {
  FieldDefinition field;
  std::size_t offset = 0;  // bytes from the payload's start
  std::size_t size = 0;    // bytes, all elements
};

class MessageDefinition {
 public:
  MessageDefinition(std::uint32_t id, std::string name, std::vector<FieldDefinition> fields);

  std::uint32_t id() const { return id_; }
  const std::string& name() const { return name_; }
  const std::vector<FieldLayout>& wire_fields() const { return wire_fields_; }
  std::size_t base_length() const { return base_length_; }  // without extensions (MAVLink 1)
  std::size_t full_length() const { return full_length_; }  // with extensions
  std::uint8_t crc_extra() const { return crc_extra_; }
  // The offset of field `name`; throws std::out_of_range for a name the message lacks.
  std::size_t offset(const std::string& name) const;

 private:
  std::uint32_t id_;
  std::string name_;
  std::vector<FieldLayout> wire_fields_;
  std::size_t base_length_ = 0;
  std::size_t full_length_ = 0;
  std::uint8_t crc_extra_ = 0;
};

// Bytes of one element of an XML field type.
std::size_t type_size(const std::string& type);

}  // namespace uavslam::mavlink
