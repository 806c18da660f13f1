// The MCAP container format (https://mcap.dev/spec, major version 0): the magic, the record
// opcodes and the records this project writes and reads, as plain structs. McapWriter encodes
// them, McapReader decodes them; neither knows anything of DDS.
//
// File layout (spec "File Structure"):
//   <Magic><Header><Data section>[<Summary section>][<Summary Offset section>]<Footer><Magic>
// Every record is <opcode u8><content length u64><content>. Integers are little-endian; a String
// is a u32 byte length and UTF-8 bytes; a Map is a u32 byte length and its key/value entries
// (spec "Serialization"). Timestamps are u64 nanoseconds; ours count from the Unix epoch.
#pragma once

#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace uavslam::io::mcap {

// Spec "Magic": 0x89 "MCAP" <major version '0'> "\r\n", at the start and at the end of a file.
inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

// Spec "Records": opcodes 0x01-0x7F belong to the format; readers skip those they do not know.
enum class Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// <opcode u8><content length u64> in front of every record's content.
inline constexpr std::size_t kRecordPrefixSize = 1 + 8;
// Spec "Footer": summary_start u64, summary_offset_start u64, summary_crc u32; never extended.
inline constexpr std::uint64_t kFooterContentSize = 8 + 8 + 4;
// Spec "Message": channel_id u16, sequence u32, log_time u64, publish_time u64, then the data.
inline constexpr std::uint64_t kMessageFieldsSize = 2 + 4 + 8 + 8;

// The record's name as the spec spells it, for error messages ("Chunk", "Message Index").
inline std::string opcode_name(std::uint8_t opcode) {
  static const char* const kNames[] = {
      "Header",     "Footer",        "Schema",         "Channel",        "Message",
      "Chunk",      "Message Index", "Chunk Index",    "Attachment",     "Attachment Index",
      "Statistics", "Metadata",      "Metadata Index", "Summary Offset", "Data End"};
  if (opcode >= 0x01 && opcode <= 0x0F) return kNames[opcode - 1];
  static const char kHex[] = "0123456789ABCDEF";
  return std::string("unknown (opcode 0x") + kHex[opcode >> 4] + kHex[opcode & 0xF] + ")";
}

// Spec "Header" (op 0x01).
struct Header {
  std::string profile;  // "" : no well-known profile (ours is CDR over OMG IDL, not ROS 2)
  std::string library;
};

// Spec "Footer" (op 0x02). Offsets are from the start of the file; 0 means "absent".
struct Footer {
  std::uint64_t summary_start = 0;
  std::uint64_t summary_offset_start = 0;
  // CRC-32 of the bytes from summary_start up to and including the footer's
  // summary_offset_start field; 0: not computed.
  std::uint32_t summary_crc = 0;
};

// Spec "Schema" (op 0x03). id 0 is invalid (it means "no schema" in a Channel).
struct Schema {
  std::uint16_t id = 0;
  std::string name;      // e.g. the IDL type "uavslam::msg::LaserScan"
  std::string encoding;  // e.g. "omgidl"
  std::string data;      // the schema's bytes (for "omgidl": the IDL text)
};

// Spec "Channel" (op 0x04).
struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;  // 0: no schema
  std::string topic;
  std::string message_encoding;  // e.g. "cdr"
  std::map<std::string, std::string> metadata;
};

// Spec "Message" (op 0x05).
struct Message {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;      // when it was recorded
  std::uint64_t publish_time = 0;  // when it was published (the log time when unknown)
  std::vector<std::uint8_t> data;  // encoded as its channel's message_encoding says
};

// Spec "Chunk Index" (op 0x08): where a Chunk and its Message Index records are.
struct ChunkIndex {
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::uint64_t chunk_start_offset = 0;
  std::uint64_t chunk_length = 0;  // the whole record, opcode and length prefix included
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;  // channel id -> file offset
  std::uint64_t message_index_length = 0;
  std::string compression;            // "" (none), "lz4" or "zstd"
  std::uint64_t compressed_size = 0;  // of the chunk's records field
  std::uint64_t uncompressed_size = 0;
};

// Spec "Statistics" (op 0x0B).
struct Statistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t message_start_time = 0;  // 0 when there are no messages
  std::uint64_t message_end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

// Spec "Summary Offset" (op 0x0E): where the summary's records of one opcode are.
struct SummaryOffset {
  std::uint8_t group_opcode = 0;
  std::uint64_t group_start = 0;
  std::uint64_t group_length = 0;
};

// The CRC-32 every MCAP checksum uses (ISO-HDLC, the one of zlib and PNG), continued from
// `crc` (0 to start): crc32_update(crc32_update(0, a), b) is the CRC of a followed by b.
inline std::uint32_t crc32_update(std::uint32_t crc, const std::uint8_t* data, std::size_t size) {
  uLong value = crc;
  while (size > 0) {  // zlib takes at most a uInt at a time
    const auto piece = static_cast<uInt>(size < (1u << 30) ? size : (1u << 30));
    value = ::crc32(value, data, piece);
    data += piece;
    size -= piece;
  }
  return static_cast<std::uint32_t>(value);
}

}  // namespace uavslam::io::mcap
