#include "RtpsTraffic.hpp"

#include <algorithm>
#include <cstring>

namespace uavslam::net {
namespace {

// Submessage ids (DDSI-RTPS 2.x, 9.4.5.1.1).
constexpr std::uint8_t kPad = 0x01;
constexpr std::uint8_t kAckNack = 0x06;
constexpr std::uint8_t kHeartbeat = 0x07;
constexpr std::uint8_t kGap = 0x08;
constexpr std::uint8_t kInfoTs = 0x09;
constexpr std::uint8_t kInfoSrc = 0x0c;
constexpr std::uint8_t kInfoDst = 0x0e;
constexpr std::uint8_t kNackFrag = 0x12;
constexpr std::uint8_t kHeartbeatFrag = 0x13;
constexpr std::uint8_t kData = 0x15;
constexpr std::uint8_t kDataFrag = 0x16;

// Submessage flags: E (endianness) on all; DATA: Q inline QoS, D data, K key; DATA_FRAG: Q.
constexpr std::uint8_t kFlagLittleEndian = 0x01;
constexpr std::uint8_t kFlagInlineQos = 0x02;
constexpr std::uint8_t kDataFlagData = 0x04;
constexpr std::uint8_t kDataFlagKey = 0x08;

// The SEDP writers, whose samples announce the publications and subscriptions.
constexpr std::uint32_t kSedpPublicationsWriter = 0x000003c2;
constexpr std::uint32_t kSedpSubscriptionsWriter = 0x000004c2;

// Parameter ids (9.6.2.2.2) and encapsulations (10.2, 10.5) of the discovery data.
constexpr std::uint16_t kPidSentinel = 0x0001;
constexpr std::uint16_t kPidTopicName = 0x0005;
constexpr std::uint16_t kPidEndpointGuid = 0x005a;
constexpr std::uint16_t kPidKeyHash = 0x0070;
constexpr std::uint16_t kPidVendorSpecific = 0x8000;
constexpr std::uint16_t kPidMustUnderstand = 0x4000;
constexpr std::uint16_t kPlCdrBigEndian = 0x0002;
constexpr std::uint16_t kPlCdrLittleEndian = 0x0003;

constexpr std::size_t kRtpsHeaderBytes = 20;  // "RTPS", version, vendorId, guidPrefix
constexpr std::size_t kPrefixBytes = 12;
constexpr std::size_t kIpv4MinHeaderBytes = 20;
constexpr std::size_t kUdpHeaderBytes = 8;
constexpr std::uint8_t kProtocolUdp = 17;
// A hostile or broken link must not grow the endpoint table without bound.
constexpr std::size_t kMaxEndpoints = 1 << 16;

using Prefix = std::array<std::uint8_t, kPrefixBytes>;

// A bounds-checked window on a packet: every read says whether its bytes were there.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::size_t size() const { return size_; }
  const std::uint8_t* data() const { return data_; }
  bool has(std::size_t offset, std::size_t count) const {
    return offset <= size_ && count <= size_ - offset;
  }
  // The bytes from `offset` on, at most `count` of them (empty past the end).
  Bytes from(std::size_t offset, std::size_t count = SIZE_MAX) const {
    if (offset > size_) return {data_, 0};
    return {data_ + offset, std::min(count, size_ - offset)};
  }
  std::optional<std::uint16_t> u16(std::size_t offset, bool little) const {
    if (!has(offset, 2)) return std::nullopt;
    const std::uint8_t* p = data_ + offset;
    return static_cast<std::uint16_t>(little ? p[0] | p[1] << 8 : p[0] << 8 | p[1]);
  }
  std::optional<std::uint32_t> u32(std::size_t offset, bool little) const {
    if (!has(offset, 4)) return std::nullopt;
    const std::uint8_t* p = data_ + offset;
    const std::uint32_t b0 = p[0], b1 = p[1], b2 = p[2], b3 = p[3];
    return little ? b0 | b1 << 8 | b2 << 16 | b3 << 24 : b0 << 24 | b1 << 16 | b2 << 8 | b3;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
};

// An EntityId is four octets in a fixed order (entityKey, entityKind), whatever the endianness.
std::optional<std::uint32_t> entity_id(const Bytes& body, std::size_t offset) {
  return body.u32(offset, false);
}

bool is_builtin(std::uint32_t entity) {
  return (entity & 0xc0u) == 0xc0u;  // entityKind's two top bits: 11 builtin, 00 user
}

Guid make_guid(const Prefix& prefix, std::uint32_t entity) {
  Guid guid{};
  std::copy(prefix.begin(), prefix.end(), guid.begin());
  for (int i = 0; i < 4; ++i)
    guid[kPrefixBytes + i] = static_cast<std::uint8_t>(entity >> (24 - 8 * i));
  return guid;
}

std::uint32_t entity_of(const Guid& guid) {
  std::uint32_t entity = 0;
  for (std::size_t i = kPrefixBytes; i < guid.size(); ++i) entity = entity << 8 | guid[i];
  return entity;
}

bool prefix_unknown(const Guid& guid) {
  return std::all_of(guid.begin(), guid.begin() + kPrefixBytes,
                     [](std::uint8_t b) { return b == 0; });
}

Prefix read_prefix(const Bytes& bytes, std::size_t offset) {
  Prefix prefix{};
  std::memcpy(prefix.data(), bytes.data() + offset, kPrefixBytes);
  return prefix;
}

Guid read_guid(const Bytes& value) {
  Guid guid{};
  std::memcpy(guid.data(), value.data(), guid.size());
  return guid;
}

// Calls on_parameter(id, value) for each parameter of a ParameterList up to its sentinel; returns
// the offset just past the sentinel, or nothing when the list is cut short.
template <typename OnParameter>
std::optional<std::size_t> walk_parameters(const Bytes& list, bool little,
                                           OnParameter on_parameter) {
  std::size_t offset = 0;
  for (;;) {
    const auto pid = list.u16(offset, little);
    const auto length = list.u16(offset + 2, little);
    if (!pid || !length) return std::nullopt;
    offset += 4;
    if (*pid == kPidSentinel) return offset;
    if (!list.has(offset, *length)) return std::nullopt;
    if ((*pid & kPidVendorSpecific) == 0) {
      on_parameter(static_cast<std::uint16_t>(*pid & ~kPidMustUnderstand),
                   list.from(offset, *length));
    }
    offset += *length;
  }
}

// A CDR string (length with its NUL, then the characters) that is a plausible topic name.
std::optional<std::string> topic_name(const Bytes& value, bool little) {
  const auto length = value.u32(0, little);
  if (!length || *length < 2 || !value.has(4, *length)) return std::nullopt;
  const char* chars = reinterpret_cast<const char*>(value.data() + 4);
  std::string name(chars, *length - 1);
  const bool printable =
      std::all_of(name.begin(), name.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
  if (!printable) return std::nullopt;
  return name;
}

// Where a DATA or DATA_FRAG submessage's serialized payload starts within its body, and the key
// hash of its inline QoS if it has one; nothing when the inline QoS is cut short.
struct PayloadStart {
  std::size_t offset = 0;
  std::optional<Guid> key_hash;
};

std::optional<PayloadStart> payload_start(const Bytes& body, std::uint8_t flags) {
  const bool little = (flags & kFlagLittleEndian) != 0;
  const auto octets_to_inline_qos = body.u16(2, little);
  if (!octets_to_inline_qos) return std::nullopt;
  PayloadStart start{4u + *octets_to_inline_qos, std::nullopt};
  if ((flags & kFlagInlineQos) == 0) return start;
  const Bytes inline_qos = body.from(start.offset);
  const auto end = walk_parameters(inline_qos, little, [&](std::uint16_t pid, const Bytes& value) {
    if (pid == kPidKeyHash && value.size() >= 16) start.key_hash = read_guid(value);
  });
  if (!end) return std::nullopt;
  start.offset += *end;
  return start;
}

// The writerId's offset in the body of the submessages that carry one (9.4.5).
std::optional<std::size_t> writer_id_offset(std::uint8_t id) {
  switch (id) {
    case kData:
    case kDataFrag:
      return 8;  // extraFlags, octetsToInlineQos, readerId
    case kHeartbeat:
    case kHeartbeatFrag:
    case kGap:
    case kAckNack:
    case kNackFrag:
      return 4;  // readerId
    default:
      return std::nullopt;
  }
}

bool names_destination_writer(std::uint8_t id) {
  return id == kAckNack || id == kNackFrag;  // sent by a reader to the writer it names
}

}  // namespace

void RtpsTraffic::add_packet(const std::uint8_t* packet, std::size_t length) {
  ++total_packets_;
  total_bytes_ += length;
  const Bytes ip(packet, length);
  std::vector<Piece> pieces;
  if (ip.has(0, kIpv4MinHeaderBytes) && packet[0] >> 4 == 4) {
    const std::size_t header = (packet[0] & 0x0fu) * 4u;
    const auto fragment = ip.u16(6, false);  // MF flag and fragment offset
    const bool whole_udp = header >= kIpv4MinHeaderBytes && ip.has(header, kUdpHeaderBytes) &&
                           packet[9] == kProtocolUdp && (*fragment & 0x3fffu) == 0;
    const auto udp_length = whole_udp ? ip.u16(header + 4, false) : std::nullopt;
    if (udp_length && *udp_length >= kUdpHeaderBytes && ip.has(header, *udp_length)) {
      pieces = submessage_pieces(packet + header + kUdpHeaderBytes, *udp_length - kUdpHeaderBytes);
    }
  }
  attribute(pieces, length);
}

std::vector<RtpsTraffic::Piece> RtpsTraffic::submessage_pieces(const std::uint8_t* data,
                                                               std::size_t length) {
  std::vector<Piece> pieces;
  const Bytes message(data, length);
  if (!message.has(0, kRtpsHeaderBytes) || std::memcmp(data, "RTPS", 4) != 0) return pieces;
  // The receiver's state (8.3.4): who sent the submessages that follow, and to whom.
  Prefix source = read_prefix(message, 8);
  Prefix destination{};  // unknown until an INFO_DST names it
  std::size_t offset = kRtpsHeaderBytes;
  while (message.has(offset, 4)) {
    const std::uint8_t id = data[offset];
    const std::uint8_t flags = data[offset + 1];
    const std::size_t octets_to_next = *message.u16(offset + 2, (flags & kFlagLittleEndian) != 0);
    const std::size_t body_offset = offset + 4;
    // 0 means "to the end of the message", except for the submessages that may be empty.
    const std::size_t body_length =
        octets_to_next == 0 && id != kPad && id != kInfoTs ? length - body_offset : octets_to_next;
    if (!message.has(body_offset, body_length)) break;  // cut short: the rest is overhead
    const Bytes body = message.from(body_offset, body_length);
    offset = body_offset + body_length;
    if (id == kInfoSrc && body.has(8, kPrefixBytes)) source = read_prefix(body, 8);
    if (id == kInfoDst && body.has(0, kPrefixBytes)) destination = read_prefix(body, 0);
    const auto writer_offset = writer_id_offset(id);
    if (!writer_offset) continue;
    const auto writer_entity = entity_id(body, *writer_offset);
    if (!writer_entity) break;  // an invalid submessage invalidates the rest of the message
    const Guid writer =
        make_guid(names_destination_writer(id) ? destination : source, *writer_entity);
    Piece piece{writer_topic(writer), 4 + body_length, id == kData ? 1u : 0u, 0};
    if (id == kDataFrag) {
      piece.fragments = body.u16(24, (flags & kFlagLittleEndian) != 0).value_or(0);
    }
    const bool sedp =
        *writer_entity == kSedpPublicationsWriter || *writer_entity == kSedpSubscriptionsWriter;
    const bool first_fragment = id == kDataFrag && body.u32(20, flags & kFlagLittleEndian) == 1u;
    const bool carries_payload =
        (id == kData && (flags & (kDataFlagData | kDataFlagKey)) != 0) || first_fragment;
    if (sedp && carries_payload) {
      if (const auto start = payload_start(body, flags)) {
        const Bytes payload = body.from(start->offset);
        learn_from_sedp(payload.data(), payload.size(),
                        start->key_hash ? &*start->key_hash : nullptr);
      }
    }
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

void RtpsTraffic::learn_from_sedp(const std::uint8_t* data, std::size_t length,
                                  const Guid* key_hash) {
  const Bytes payload(data, length);
  const auto encapsulation = payload.u16(0, false);
  if (!encapsulation ||
      (*encapsulation != kPlCdrBigEndian && *encapsulation != kPlCdrLittleEndian)) {
    return;
  }
  const bool little = *encapsulation == kPlCdrLittleEndian;
  std::optional<std::string> topic;
  std::optional<Guid> endpoint;
  if (key_hash != nullptr) endpoint = *key_hash;  // the key of SEDP data is the endpoint GUID
  // A first fragment holds only the list's beginning: what it has is used, cut short or not.
  walk_parameters(payload.from(4), little, [&](std::uint16_t pid, const Bytes& value) {
    if (pid == kPidTopicName) topic = topic_name(value, little);
    if (pid == kPidEndpointGuid && value.size() >= 16) endpoint = read_guid(value);
  });
  if (!topic || !endpoint) return;
  if (endpoint_topics_.size() >= kMaxEndpoints && endpoint_topics_.count(*endpoint) == 0) return;
  endpoint_topics_[*endpoint] = *topic;
}

std::string RtpsTraffic::writer_topic(const Guid& writer) const {
  const std::uint32_t entity = entity_of(writer);
  if (is_builtin(entity)) return kDiscovery;
  const auto known = endpoint_topics_.find(writer);
  if (known != endpoint_topics_.end()) return known->second;
  if (!prefix_unknown(writer)) return kUnknown;
  // No INFO_DST: the writer is in the receiving participant, which the packet does not name; the
  // entity id alone decides when every known endpoint with it is on one topic.
  std::optional<std::string> only;
  for (const auto& [guid, topic] : endpoint_topics_) {
    if (entity_of(guid) != entity) continue;
    if (only && *only != topic) return kUnknown;
    only = topic;
  }
  return only.value_or(kUnknown);
}

void RtpsTraffic::attribute(const std::vector<Piece>& pieces, std::size_t packet_length) {
  if (pieces.empty()) {
    TopicTraffic& other = topics_[kOther];
    other.bytes += packet_length;
    other.packets_share += 1.0;
    return;
  }
  std::uint64_t attributed = 0;
  for (const Piece& piece : pieces) attributed += piece.bytes;
  const std::uint64_t overhead = packet_length - attributed;
  // Cumulative rounding: the shares of the overhead add up to it exactly.
  std::uint64_t cumulative = 0, given = 0;
  for (const Piece& piece : pieces) {
    cumulative += piece.bytes;
    const std::uint64_t due = overhead * cumulative / attributed;
    const std::uint64_t bytes = piece.bytes + (due - given);
    given = due;
    TopicTraffic& topic = topics_[piece.topic];
    topic.bytes += bytes;
    topic.packets_share += static_cast<double>(bytes) / static_cast<double>(packet_length);
    topic.data += piece.data;
    topic.fragments += piece.fragments;
  }
}

std::optional<std::string> RtpsTraffic::topic_of(const Guid& endpoint) const {
  const auto known = endpoint_topics_.find(endpoint);
  if (known == endpoint_topics_.end()) return std::nullopt;
  return known->second;
}

}  // namespace uavslam::net
