// Which DDS topic the bytes on a link belong to: fed with every IPv4 packet the link carries (as
// NFQUEUE hands it over: IPv4 header, UDP header, payload), it parses the RTPS messages (OMG
// DDSI-RTPS 2.x, 8.3 and 9.4), learns endpoint GUID -> topic from the SEDP announcements that
// cross the link, and attributes each packet's bytes to the topics of its submessages:
//  - DATA, DATA_FRAG, HEARTBEAT, HEARTBEAT_FRAG, GAP: the writer {source prefix, writerId};
//  - ACKNACK, NACK_FRAG: the writer {destination prefix (INFO_DST), writerId};
//  - a builtin writer (SPDP, SEDP, WLP, type lookup) -> "discovery", a user writer not (yet) named
//    -> "unknown", anything that is not UDP RTPS (or an IP fragment, or garbage) -> "other".
// A packet's headers (IP, UDP, RTPS header, INFO_* and other unattributed submessages) are split
// over its attributed submessages in proportion to their sizes, so the topics' bytes add up to
// the packets' lengths exactly. Never reads outside the packet it is given.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace uavslam::net {

// What one topic (or "discovery", "unknown", "other") took of the link.
struct TopicTraffic {
  std::uint64_t bytes = 0;      // IP bytes, headers shared out
  double packets_share = 0.0;   // each packet counts 1, shared by its topics in proportion to bytes
  std::uint64_t data = 0;       // DATA submessages (samples, repairs included)
  std::uint64_t fragments = 0;  // fragments carried by DATA_FRAG submessages
};

using Guid = std::array<std::uint8_t, 16>;  // guidPrefix (12) + entityId (4)

class RtpsTraffic {
 public:
  static constexpr const char* kDiscovery = "discovery";
  static constexpr const char* kUnknown = "unknown";
  static constexpr const char* kOther = "other";

  // One IPv4 packet of `length` bytes, all of it on the wire.
  void add_packet(const std::uint8_t* packet, std::size_t length);

  const std::map<std::string, TopicTraffic>& topics() const { return topics_; }
  std::uint64_t total_bytes() const { return total_bytes_; }
  std::uint64_t total_packets() const { return total_packets_; }

  // The topic an endpoint (writer or reader) announced through SEDP, if it was seen.
  std::optional<std::string> topic_of(const Guid& endpoint) const;

 private:
  // One attributed submessage of a packet.
  struct Piece {
    std::string topic;
    std::size_t bytes = 0;
    std::uint64_t data = 0;
    std::uint64_t fragments = 0;
  };

  std::vector<Piece> submessage_pieces(const std::uint8_t* message, std::size_t length);
  void learn_from_sedp(const std::uint8_t* payload, std::size_t length, const Guid* key_hash);
  void attribute(const std::vector<Piece>& pieces, std::size_t packet_length);
  std::string writer_topic(const Guid& writer) const;

  std::map<std::string, TopicTraffic> topics_;
  std::map<Guid, std::string> endpoint_topics_;
  std::uint64_t total_bytes_ = 0;
  std::uint64_t total_packets_ = 0;
};

}  // namespace uavslam::net
