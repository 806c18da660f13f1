#include "drivers/mavlink/FrameWriter.hpp"

#include <stdexcept>

#include "drivers/mavlink/Crc.hpp"

namespace uavslam::mavlink {
namespace {

std::size_t truncated_length(const std::vector<std::uint8_t>& payload) {
  std::size_t length = payload.size();
  while (length > 1 && payload[length - 1] == 0) --length;
  return length;
}

}  // namespace

std::vector<std::uint8_t> FrameWriter::frame(MessageId id, const std::vector<std::uint8_t>& payload,
                                             const std::optional<Signature>& signature) {
  const MessageDefinition& message = definition(id);
  std::vector<std::uint8_t> out;
  std::size_t length = 0;
  if (version_ == 1) {
    if (id > 255) throw std::invalid_argument("message " + message.name() + " needs MAVLink 2");
    length = std::min(payload.size(), message.base_length());
    out = {kStxV1,        static_cast<std::uint8_t>(length), sequence_, system_id_,
           component_id_, static_cast<std::uint8_t>(id)};
  } else {
    length = truncated_length(payload);
    const std::uint8_t incompat = signature ? kIncompatSigned : 0;
    out = {kStxV2,
           static_cast<std::uint8_t>(length),
           incompat,
           0,
           sequence_,
           system_id_,
           component_id_,
           static_cast<std::uint8_t>(id & 0xFF),
           static_cast<std::uint8_t>((id >> 8) & 0xFF),
           static_cast<std::uint8_t>((id >> 16) & 0xFF)};
  }
  out.insert(out.end(), payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(length));
  std::uint16_t crc = crc_accumulate(out.data() + 1, out.size() - 1, kCrcInit);
  crc = crc_accumulate(message.crc_extra(), crc);
  out.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  out.push_back(static_cast<std::uint8_t>(crc >> 8));
  if (version_ == 2 && signature) {
    out.push_back(signature->link_id);
    for (int i = 0; i < 6; ++i) {
      out.push_back(static_cast<std::uint8_t>(signature->timestamp >> (8 * i)));
    }
    out.insert(out.end(), signature->hash.begin(), signature->hash.end());
  }
  ++sequence_;
  return out;
}

}  // namespace uavslam::mavlink
