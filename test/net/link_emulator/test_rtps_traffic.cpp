// RtpsTraffic on hand-built IPv4/UDP/RTPS packets: topics learned from SEDP, DATA, DATA_FRAG,
// ACKNACK through INFO_DST, headers shared so totals add up, and garbage counted as "other".
#include "RtpsTraffic.hpp"

#include <cstdint>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace uavslam::net {
namespace {

using Bytes = std::vector<std::uint8_t>;
using Prefix = std::array<std::uint8_t, 12>;

constexpr Prefix kUav{1, 15, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
constexpr Prefix kGcs{1, 15, 9, 9, 9, 9, 5, 6, 7, 8, 9, 11};
constexpr std::uint32_t kScanWriter = 0x00000103;  // a user writer without key
constexpr std::uint32_t kScanReader = 0x00000204;  // a user reader without key
constexpr std::uint32_t kSedpPublications = 0x000003c2;
constexpr std::uint32_t kSedpSubscriptions = 0x000004c2;
constexpr std::uint32_t kSpdpWriter = 0x000100c2;

void put16(Bytes& out, std::uint16_t v, bool little) {
  out.push_back(static_cast<std::uint8_t>(little ? v : v >> 8));
  out.push_back(static_cast<std::uint8_t>(little ? v >> 8 : v));
}

void put32(Bytes& out, std::uint32_t v, bool little) {
  for (int i = 0; i < 4; ++i) {
    const int shift = little ? 8 * i : 24 - 8 * i;
    out.push_back(static_cast<std::uint8_t>(v >> shift));
  }
}

void put_entity(Bytes& out, std::uint32_t entity) {
  put32(out, entity, false);  // EntityIds have one octet order
}

Guid guid(const Prefix& prefix, std::uint32_t entity) {
  Guid g{};
  std::copy(prefix.begin(), prefix.end(), g.begin());
  for (int i = 0; i < 4; ++i) g[12 + i] = static_cast<std::uint8_t>(entity >> (24 - 8 * i));
  return g;
}

// An SEDP sample (PL_CDR_LE or _BE): topic name and endpoint GUID, then the sentinel.
Bytes sedp_payload(const std::string& topic, const Guid& endpoint, bool little = true) {
  Bytes out{0x00, static_cast<std::uint8_t>(little ? 0x03 : 0x02), 0x00, 0x00};
  const std::uint32_t chars = static_cast<std::uint32_t>(topic.size() + 1);
  const std::uint32_t padded = (4 + chars + 3) / 4 * 4;
  put16(out, 0x0005, little);
  put16(out, static_cast<std::uint16_t>(padded), little);
  put32(out, chars, little);
  out.insert(out.end(), topic.begin(), topic.end());
  out.resize(out.size() + (padded - 4 - topic.size()), 0);
  put16(out, 0x005a, little);
  put16(out, 16, little);
  out.insert(out.end(), endpoint.begin(), endpoint.end());
  put16(out, 0x0001, little);
  put16(out, 0, little);
  return out;
}

// One RTPS message from participant `source`, built submessage by submessage.
class RtpsMessage {
 public:
  explicit RtpsMessage(const Prefix& source) : bytes_{'R', 'T', 'P', 'S', 2, 3, 1, 15} {
    bytes_.insert(bytes_.end(), source.begin(), source.end());
  }

  RtpsMessage& info_ts() { return submessage(0x09, 0x01, Bytes(8, 0)); }
  RtpsMessage& info_dst(const Prefix& destination) {
    return submessage(0x0e, 0x01, Bytes(destination.begin(), destination.end()));
  }
  RtpsMessage& info_src(const Prefix& source) {
    Bytes body(8, 0);
    body.insert(body.end(), source.begin(), source.end());
    return submessage(0x0c, 0x01, body);
  }
  RtpsMessage& data(std::uint32_t writer, const Bytes& payload, bool little = true) {
    Bytes body;
    put16(body, 0, little);   // extraFlags
    put16(body, 16, little);  // octetsToInlineQos
    put_entity(body, 0);      // readerId: unknown
    put_entity(body, writer);
    put32(body, 0, little);  // writerSN high
    put32(body, 1, little);  // writerSN low
    body.insert(body.end(), payload.begin(), payload.end());
    return submessage(0x15, (little ? 0x01 : 0x00) | 0x04, body);
  }
  RtpsMessage& data_frag(std::uint32_t writer, std::uint32_t first, std::uint16_t count,
                         const Bytes& fragments, bool little = true) {
    Bytes body;
    put16(body, 0, little);
    put16(body, 28, little);
    put_entity(body, 0);
    put_entity(body, writer);
    put32(body, 0, little);
    put32(body, 1, little);
    put32(body, first, little);
    put16(body, count, little);
    put16(body, 1344, little);  // fragmentSize
    put32(body, 4404, little);  // sampleSize
    body.insert(body.end(), fragments.begin(), fragments.end());
    return submessage(0x16, little ? 0x01 : 0x00, body);
  }
  RtpsMessage& heartbeat(std::uint32_t writer) {
    Bytes body;
    put_entity(body, 0);
    put_entity(body, writer);
    body.resize(body.size() + 20, 0);  // firstSN, lastSN, count
    return submessage(0x07, 0x01, body);
  }
  RtpsMessage& acknack(std::uint32_t reader, std::uint32_t writer) {
    Bytes body;
    put_entity(body, reader);
    put_entity(body, writer);
    body.resize(body.size() + 16, 0);  // readerSNState (empty set), count
    return submessage(0x06, 0x01, body);
  }

  // The message in an IPv4/UDP packet: 20 + 8 bytes of headers.
  Bytes packet() const {
    Bytes out{0x45, 0x00};
    put16(out, static_cast<std::uint16_t>(28 + bytes_.size()), false);
    out.insert(out.end(), {0, 0, 0x40, 0x00, 64, 17, 0, 0, 10, 200, 0, 1, 10, 200, 0, 2});
    put16(out, 7410, false);
    put16(out, 7411, false);
    put16(out, static_cast<std::uint16_t>(8 + bytes_.size()), false);
    put16(out, 0, false);
    out.insert(out.end(), bytes_.begin(), bytes_.end());
    return out;
  }

 private:
  RtpsMessage& submessage(std::uint8_t id, std::uint8_t flags, const Bytes& body) {
    bytes_.push_back(id);
    bytes_.push_back(flags);
    put16(bytes_, static_cast<std::uint16_t>(body.size()), (flags & 0x01) != 0);
    bytes_.insert(bytes_.end(), body.begin(), body.end());
    return *this;
  }

  Bytes bytes_;
};

void feed(RtpsTraffic& traffic, const Bytes& packet) {
  traffic.add_packet(packet.data(), packet.size());
}

std::uint64_t bytes_of(const RtpsTraffic& traffic, const std::string& topic) {
  const auto found = traffic.topics().find(topic);
  return found == traffic.topics().end() ? 0 : found->second.bytes;
}

std::uint64_t sum_of_topics(const RtpsTraffic& traffic) {
  std::uint64_t sum = 0;
  for (const auto& [name, topic] : traffic.topics()) sum += topic.bytes;
  return sum;
}

double packets_of_topics(const RtpsTraffic& traffic) {
  double sum = 0.0;
  for (const auto& [name, topic] : traffic.topics()) sum += topic.packets_share;
  return sum;
}

Bytes scan_announcement() {
  return RtpsMessage(kUav)
      .info_ts()
      .data(kSedpPublications, sedp_payload("uav1/scan", guid(kUav, kScanWriter)))
      .packet();
}

TEST(RtpsTraffic, DataOfAnAnnouncedWriterGoesToItsTopic) {
  RtpsTraffic traffic;
  const Bytes announcement = scan_announcement();
  feed(traffic, announcement);
  EXPECT_EQ(traffic.topic_of(guid(kUav, kScanWriter)), "uav1/scan");
  const Bytes sample = RtpsMessage(kUav).info_ts().data(kScanWriter, Bytes(400, 7)).packet();
  feed(traffic, sample);

  EXPECT_EQ(bytes_of(traffic, "discovery"), announcement.size());
  const TopicTraffic& scan = traffic.topics().at("uav1/scan");
  EXPECT_EQ(scan.bytes, sample.size());
  EXPECT_EQ(scan.data, 1u);
  EXPECT_DOUBLE_EQ(scan.packets_share, 1.0);
  EXPECT_EQ(traffic.total_bytes(), announcement.size() + sample.size());
  EXPECT_EQ(traffic.total_packets(), 2u);
}

TEST(RtpsTraffic, DataOfAWriterNotYetAnnouncedIsUnknown) {
  RtpsTraffic traffic;
  const Bytes sample = RtpsMessage(kUav).data(kScanWriter, Bytes(40, 1)).packet();
  feed(traffic, sample);
  EXPECT_EQ(bytes_of(traffic, "unknown"), sample.size());
  feed(traffic, scan_announcement());
  feed(traffic, sample);
  EXPECT_EQ(bytes_of(traffic, "uav1/scan"), sample.size());
}

TEST(RtpsTraffic, BigEndianSubscriptionAnnouncementNamesTheReader) {
  RtpsTraffic traffic;
  feed(traffic, RtpsMessage(kGcs)
                    .data(kSedpSubscriptions,
                          sedp_payload("uav1/pose", guid(kGcs, kScanReader), false), false)
                    .packet());
  EXPECT_EQ(traffic.topic_of(guid(kGcs, kScanReader)), "uav1/pose");
}

TEST(RtpsTraffic, DataFragCountsItsFragmentsOnTheTopic) {
  RtpsTraffic traffic;
  feed(traffic, scan_announcement());
  const Bytes first =
      RtpsMessage(kUav).info_ts().data_frag(kScanWriter, 1, 1, Bytes(1344, 3)).packet();
  const Bytes rest = RtpsMessage(kUav).data_frag(kScanWriter, 2, 3, Bytes(1000, 3), false).packet();
  feed(traffic, first);
  feed(traffic, rest);
  const TopicTraffic& scan = traffic.topics().at("uav1/scan");
  EXPECT_EQ(scan.bytes, first.size() + rest.size());
  EXPECT_EQ(scan.fragments, 4u);
  EXPECT_EQ(scan.data, 0u);
}

TEST(RtpsTraffic, AnAnnouncementInAFirstFragmentIsLearned) {
  RtpsTraffic traffic;
  feed(traffic,
       RtpsMessage(kUav)
           .data_frag(kSedpPublications, 1, 1, sedp_payload("uav1/map", guid(kUav, kScanWriter)))
           .packet());
  EXPECT_EQ(traffic.topic_of(guid(kUav, kScanWriter)), "uav1/map");
}

TEST(RtpsTraffic, AckNackGoesToTheWriterNamedThroughInfoDst) {
  RtpsTraffic traffic;
  feed(traffic, scan_announcement());
  const Bytes ack = RtpsMessage(kGcs).info_dst(kUav).acknack(kScanReader, kScanWriter).packet();
  feed(traffic, ack);
  EXPECT_EQ(bytes_of(traffic, "uav1/scan"), ack.size());
  // The same reader's ACKNACK to a participant nobody announced.
  const Bytes elsewhere =
      RtpsMessage(kGcs).info_dst(kGcs).acknack(kScanReader, kScanWriter).packet();
  feed(traffic, elsewhere);
  EXPECT_EQ(bytes_of(traffic, "unknown"), elsewhere.size());
}

TEST(RtpsTraffic, InfoSrcChangesTheWriterOfWhatFollows) {
  RtpsTraffic traffic;
  feed(traffic, scan_announcement());
  const Bytes relayed = RtpsMessage(kGcs).info_src(kUav).heartbeat(kScanWriter).packet();
  feed(traffic, relayed);
  EXPECT_EQ(bytes_of(traffic, "uav1/scan"), relayed.size());
}

TEST(RtpsTraffic, BuiltinWritersAreDiscovery) {
  RtpsTraffic traffic;
  const Bytes spdp = RtpsMessage(kUav).data(kSpdpWriter, Bytes(200, 0)).packet();
  const Bytes ack =
      RtpsMessage(kGcs).info_dst(kUav).acknack(0x000003c7, kSedpPublications).packet();
  feed(traffic, spdp);
  feed(traffic, ack);
  EXPECT_EQ(bytes_of(traffic, "discovery"), spdp.size() + ack.size());
}

TEST(RtpsTraffic, HeadersAreSharedSoTopicsAddUpToThePackets) {
  RtpsTraffic traffic;
  feed(traffic, scan_announcement());
  feed(traffic, RtpsMessage(kUav)
                    .data(kSedpPublications, sedp_payload("uav1/pose", guid(kUav, 0x00000303)))
                    .packet());
  const Bytes mixed = RtpsMessage(kUav)
                          .info_ts()
                          .data(kScanWriter, Bytes(301, 1))
                          .heartbeat(0x00000303)
                          .data(0x00000303, Bytes(57, 2))
                          .info_dst(kGcs)
                          .heartbeat(kScanWriter)
                          .packet();
  const std::uint64_t before = sum_of_topics(traffic);
  feed(traffic, mixed);
  EXPECT_EQ(sum_of_topics(traffic) - before, mixed.size());
  EXPECT_EQ(sum_of_topics(traffic), traffic.total_bytes());
  EXPECT_NEAR(packets_of_topics(traffic), 3.0, 1e-9);
  // 76 header bytes (IP 20, UDP 8, RTPS 20, INFO_TS 12, INFO_DST 16) shared by the scan's DATA
  // (325) and HEARTBEAT (32) and the pose's HEARTBEAT (32) and DATA (81).
  const std::uint64_t scan = bytes_of(traffic, "uav1/scan");
  const std::uint64_t pose = bytes_of(traffic, "uav1/pose");
  EXPECT_GT(scan, 357u);
  EXPECT_GT(pose, 113u);
  EXPECT_EQ(scan + pose, mixed.size());
}

TEST(RtpsTraffic, WhatIsNotWholeUdpRtpsIsOther) {
  RtpsTraffic traffic;
  Bytes tcp = RtpsMessage(kUav).data(kScanWriter, Bytes(10, 0)).packet();
  tcp[9] = 6;
  Bytes fragment = RtpsMessage(kUav).data(kScanWriter, Bytes(10, 0)).packet();
  fragment[6] = 0x20;  // more fragments
  Bytes not_rtps = RtpsMessage(kUav).data(kScanWriter, Bytes(10, 0)).packet();
  not_rtps[28] = 'X';
  const Bytes only_info = RtpsMessage(kUav).info_ts().info_dst(kGcs).packet();
  for (const Bytes& packet : {tcp, fragment, not_rtps, only_info}) feed(traffic, packet);
  feed(traffic, Bytes{});
  EXPECT_EQ(traffic.topics().size(), 1u);
  EXPECT_EQ(bytes_of(traffic, "other"),
            tcp.size() + fragment.size() + not_rtps.size() + only_info.size());
  EXPECT_EQ(traffic.total_packets(), 5u);
}

TEST(RtpsTraffic, TruncatedPacketsNeverReadPastTheirEnd) {
  RtpsTraffic traffic;
  const Bytes whole =
      RtpsMessage(kUav)
          .info_ts()
          .data(kSedpPublications, sedp_payload("uav1/scan", guid(kUav, kScanWriter)))
          .data_frag(kScanWriter, 1, 1, Bytes(100, 1))
          .info_dst(kGcs)
          .acknack(kScanReader, kScanWriter)
          .packet();
  std::uint64_t fed = 0;
  for (std::size_t length = 0; length <= whole.size(); ++length) {
    // A copy of exactly `length` bytes, so a sanitizer sees any read past it, whose IP and UDP
    // lengths say it ends there: the RTPS walk meets every cut.
    Bytes cut(whole.begin(), whole.begin() + static_cast<long>(length));
    if (length >= 28) {
      cut[2] = static_cast<std::uint8_t>(length >> 8);
      cut[3] = static_cast<std::uint8_t>(length);
      cut[24] = static_cast<std::uint8_t>((length - 20) >> 8);
      cut[25] = static_cast<std::uint8_t>(length - 20);
    }
    feed(traffic, cut);
    fed += length;
    EXPECT_EQ(sum_of_topics(traffic), fed) << length;
  }
  EXPECT_EQ(traffic.topic_of(guid(kUav, kScanWriter)), "uav1/scan");
  EXPECT_GT(bytes_of(traffic, "other"), 0u);
  EXPECT_GT(bytes_of(traffic, "uav1/scan"), 0u);
}

TEST(RtpsTraffic, GarbageAfterAValidHeaderIsCountedAndSurvived) {
  RtpsTraffic traffic;
  std::mt19937 random(7);
  std::uint64_t fed = 0;
  for (int i = 0; i < 2000; ++i) {
    // A valid IP/UDP/RTPS header followed by random submessage bytes with plausible ids.
    Bytes packet = RtpsMessage(kUav).packet();
    const std::size_t extra = random() % 200;
    for (std::size_t k = 0; k < extra; ++k) packet.push_back(static_cast<std::uint8_t>(random()));
    if (extra > 0) packet[48] = static_cast<std::uint8_t>(0x05 + random() % 0x12);
    packet[2] = static_cast<std::uint8_t>(packet.size() >> 8);
    packet[3] = static_cast<std::uint8_t>(packet.size());
    packet[24] = static_cast<std::uint8_t>((packet.size() - 20) >> 8);
    packet[25] = static_cast<std::uint8_t>(packet.size() - 20);
    feed(traffic, packet);
    fed += packet.size();
  }
  EXPECT_EQ(sum_of_topics(traffic), fed);
  EXPECT_NEAR(packets_of_topics(traffic), 2000.0, 1e-6);
}

}  // namespace
}  // namespace uavslam::net
