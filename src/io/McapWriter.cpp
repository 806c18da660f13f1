#include "io/McapWriter.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace uavslam::io {

namespace {

using Bytes = std::vector<std::uint8_t>;
using mcap::Opcode;

// Spec "Chunk": message_start_time, message_end_time, uncompressed_size, uncompressed_crc,
// compression (a String: its u32 length here, its text added), then the u64 length of the
// records field.
constexpr std::uint64_t kChunkFieldsSize = 8 + 8 + 8 + 4 + 4 + 8;
constexpr std::size_t kMaxIds = std::numeric_limits<std::uint16_t>::max();

// Spec "Fixed-width types": little-endian, whatever the host's byte order.
template <typename T>
void put_le(Bytes& out, T value) {
  static_assert(std::is_unsigned_v<T>);
  for (std::size_t i = 0; i < sizeof(T); ++i)
    out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

std::uint32_t u32_length(std::size_t size) {
  if (size > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("MCAP string or map of " + std::to_string(size) +
                                " bytes (more than a u32 length can say)");
  }
  return static_cast<std::uint32_t>(size);
}

// Spec "String" (and "uint32 length-prefixed Bytes", encoded the same way).
void put_string(Bytes& out, const std::string& text) {
  put_le(out, u32_length(text.size()));
  out.insert(out.end(), text.begin(), text.end());
}

// Spec "Map<string, string>": u32 byte length of the entries, then key, value, key, value...
void put_map(Bytes& out, const std::map<std::string, std::string>& map) {
  Bytes entries;
  for (const auto& [key, value] : map) {
    put_string(entries, key);
    put_string(entries, value);
  }
  put_le(out, u32_length(entries.size()));
  out.insert(out.end(), entries.begin(), entries.end());
}

// Spec "Map<uint16, uint64>".
void put_map(Bytes& out, const std::map<std::uint16_t, std::uint64_t>& map) {
  put_le(out, u32_length(map.size() * (2 + 8)));
  for (const auto& [key, value] : map) {
    put_le(out, key);
    put_le(out, value);
  }
}

// Spec "Records": <opcode u8><content length u64><content>.
void put_record(Bytes& out, Opcode opcode, const Bytes& content) {
  put_le(out, static_cast<std::uint8_t>(opcode));
  put_le(out, static_cast<std::uint64_t>(content.size()));
  out.insert(out.end(), content.begin(), content.end());
}

// Spec "Header".
Bytes header_content(const mcap::Header& header) {
  Bytes content;
  put_string(content, header.profile);
  put_string(content, header.library);
  return content;
}

// Spec "Schema".
Bytes schema_content(const mcap::Schema& schema) {
  Bytes content;
  put_le(content, schema.id);
  put_string(content, schema.name);
  put_string(content, schema.encoding);
  put_string(content, schema.data);
  return content;
}

// Spec "Channel".
Bytes channel_content(const mcap::Channel& channel) {
  Bytes content;
  put_le(content, channel.id);
  put_le(content, channel.schema_id);
  put_string(content, channel.topic);
  put_string(content, channel.message_encoding);
  put_map(content, channel.metadata);
  return content;
}

// Spec "Message Index": channel_id, then Array<Tuple<Timestamp, uint64>> of (log_time, offset
// of the Message record from the start of the chunk's uncompressed records).
Bytes message_index_content(std::uint16_t channel_id,
                            const std::vector<std::pair<std::uint64_t, std::uint64_t>>& entries) {
  Bytes content;
  put_le(content, channel_id);
  put_le(content, u32_length(entries.size() * (8 + 8)));
  for (const auto& [log_time, offset] : entries) {
    put_le(content, log_time);
    put_le(content, offset);
  }
  return content;
}

// Spec "Chunk Index".
Bytes chunk_index_content(const mcap::ChunkIndex& index) {
  Bytes content;
  put_le(content, index.message_start_time);
  put_le(content, index.message_end_time);
  put_le(content, index.chunk_start_offset);
  put_le(content, index.chunk_length);
  put_map(content, index.message_index_offsets);
  put_le(content, index.message_index_length);
  put_string(content, index.compression);
  put_le(content, index.compressed_size);
  put_le(content, index.uncompressed_size);
  return content;
}

// Spec "Statistics".
Bytes statistics_content(const mcap::Statistics& statistics) {
  Bytes content;
  put_le(content, statistics.message_count);
  put_le(content, statistics.schema_count);
  put_le(content, statistics.channel_count);
  put_le(content, statistics.attachment_count);
  put_le(content, statistics.metadata_count);
  put_le(content, statistics.chunk_count);
  put_le(content, statistics.message_start_time);
  put_le(content, statistics.message_end_time);
  put_map(content, statistics.channel_message_counts);
  return content;
}

// Spec "Summary Offset".
Bytes summary_offset_content(const mcap::SummaryOffset& offset) {
  Bytes content;
  put_le(content, offset.group_opcode);
  put_le(content, offset.group_start);
  put_le(content, offset.group_length);
  return content;
}

std::uint32_t crc32_of(const Bytes& bytes) {
  return mcap::crc32_update(0, bytes.data(), bytes.size());
}

}  // namespace

McapWriter::McapWriter(const std::string& path, McapWriterOptions options)
    : path_(path), options_(std::move(options)) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw file_error(path, std::string("cannot create: ") + std::strerror(errno));
  Bytes start(std::begin(mcap::kMagic), std::end(mcap::kMagic));
  put_record(start, Opcode::kHeader, header_content({options_.profile, options_.library}));
  try {
    put(start);
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

McapWriter::~McapWriter() {
  try {
    close();
  } catch (...) {  // a destructor cannot report; close() can
  }
  if (fd_ >= 0) ::close(fd_);
}

std::uint16_t McapWriter::add_schema(const std::string& name, const std::string& encoding,
                                     const std::string& data) {
  for (const mcap::Schema& schema : schemas_) {
    if (schema.name == name && schema.encoding == encoding && schema.data == data) {
      return schema.id;
    }
  }
  if (schemas_.size() >= kMaxIds) throw std::invalid_argument("more than 65535 MCAP schemas");
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);
  schemas_.push_back({id, name, encoding, data});
  return id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, const std::string& topic,
                                      const std::string& message_encoding,
                                      const std::map<std::string, std::string>& metadata) {
  if (schema_id > schemas_.size()) {
    throw std::invalid_argument("MCAP channel " + topic + " of unknown schema id " +
                                std::to_string(schema_id));
  }
  for (const mcap::Channel& channel : channels_) {
    if (channel.schema_id == schema_id && channel.topic == topic &&
        channel.message_encoding == message_encoding && channel.metadata == metadata) {
      return channel.id;
    }
  }
  if (channels_.size() >= kMaxIds) throw std::invalid_argument("more than 65535 MCAP channels");
  const auto id = static_cast<std::uint16_t>(channels_.size() + 1);
  channels_.push_back({id, schema_id, topic, message_encoding, metadata});
  return id;
}

void McapWriter::write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns,
                       std::uint64_t publish_time_ns, const std::uint8_t* data, std::size_t size) {
  if (channel_id == 0 || channel_id > channels_.size()) {
    throw std::invalid_argument("MCAP message on unknown channel id " + std::to_string(channel_id));
  }
  check_writable("write");
  add_to_chunk(channels_[channel_id - 1]);
  Bytes& records = chunk_.records;
  const std::uint64_t offset = records.size();
  // Spec "Message".
  put_le(records, static_cast<std::uint8_t>(Opcode::kMessage));
  put_le(records, static_cast<std::uint64_t>(mcap::kMessageFieldsSize + size));
  put_le(records, channel_id);
  put_le(records, sequence);
  put_le(records, log_time_ns);
  put_le(records, publish_time_ns);
  records.insert(records.end(), data, data + size);
  if (chunk_.message_index.empty() || log_time_ns < chunk_.message_start_time) {
    chunk_.message_start_time = log_time_ns;
  }
  if (chunk_.message_index.empty() || log_time_ns > chunk_.message_end_time) {
    chunk_.message_end_time = log_time_ns;
  }
  chunk_.message_index[channel_id].emplace_back(log_time_ns, offset);
  count_message(channel_id, log_time_ns);
  if (records.size() >= options_.chunk_size) close_chunk();
}

void McapWriter::flush() {
  check_writable("flush");
  close_chunk();
  if (options_.sync_on_flush) sync();
}

void McapWriter::close() {
  if (fd_ < 0) return;
  if (failed_) {  // the error was reported when it happened; the file stays as it is
    ::close(fd_);
    fd_ = -1;
    return;
  }
  close_chunk();
  Bytes data_end;  // Spec "Data End": the CRC of every byte before this record.
  Bytes crc;
  put_le(crc, data_section_crc_);
  put_record(data_end, Opcode::kDataEnd, crc);
  put(data_end);
  put(summary_and_footer());
  sync();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("cannot close");
}

std::uint64_t McapWriter::bytes_written() const {
  return offset_ + chunk_.records.size();
}

// Spec "Chunk": the chunk's messages must reference Schemas and Channels recorded earlier; we
// put them into the chunk itself before its first message on them, so that a chunk read on its
// own (the file cut short, or an indexed read) needs nothing else.
void McapWriter::add_to_chunk(const mcap::Channel& channel) {
  auto& has_channel = chunk_.has_channel;
  if (has_channel.size() <= channel.id) has_channel.resize(channel.id + 1u, false);
  if (has_channel[channel.id]) return;
  auto& has_schema = chunk_.has_schema;
  if (has_schema.size() <= channel.schema_id) has_schema.resize(channel.schema_id + 1u, false);
  if (channel.schema_id != 0 && !has_schema[channel.schema_id]) {
    put_record(chunk_.records, Opcode::kSchema, schema_content(schemas_[channel.schema_id - 1]));
    has_schema[channel.schema_id] = true;
  }
  put_record(chunk_.records, Opcode::kChannel, channel_content(channel));
  has_channel[channel.id] = true;
}

// Writes the open chunk (Spec "Chunk": its records compressed whole, the CRC and size of the
// uncompressed records) and its Message Index records (Spec "Message Index": one per channel in
// the chunk, right after it, offsets into the uncompressed records), and keeps its Chunk Index.
void McapWriter::close_chunk() {
  if (chunk_.message_index.empty()) return;
  const Bytes& records = chunk_.records;
  const bool compressed = options_.compression != McapCompression::kNone;
  Bytes compressed_records;
  if (compressed) {
    compressed_records =
        compress_chunk_records(options_.compression, records.data(), records.size());
  }
  const Bytes& stored = compressed ? compressed_records : records;
  mcap::ChunkIndex index;
  index.message_start_time = chunk_.message_start_time;
  index.message_end_time = chunk_.message_end_time;
  index.chunk_start_offset = offset_;
  index.compression = mcap_chunk_compression_field(options_.compression);
  index.compressed_size = stored.size();
  index.uncompressed_size = records.size();
  Bytes head;
  put_le(head, static_cast<std::uint8_t>(Opcode::kChunk));
  put_le(head, kChunkFieldsSize + index.compression.size() + stored.size());
  put_le(head, chunk_.message_start_time);
  put_le(head, chunk_.message_end_time);
  put_le(head, index.uncompressed_size);
  put_le(head, crc32_of(records));
  put_string(head, index.compression);
  put_le(head, static_cast<std::uint64_t>(stored.size()));
  put(head);
  put(stored);
  index.chunk_length = offset_ - index.chunk_start_offset;
  Bytes message_indexes;
  for (const auto& [channel_id, entries] : chunk_.message_index) {
    index.message_index_offsets[channel_id] = offset_ + message_indexes.size();
    put_record(message_indexes, Opcode::kMessageIndex, message_index_content(channel_id, entries));
  }
  index.message_index_length = message_indexes.size();
  put(message_indexes);
  chunk_indexes_.push_back(std::move(index));
  ++statistics_.chunk_count;
  clear_chunk();
}

void McapWriter::clear_chunk() {
  chunk_.records.clear();  // keeps its capacity for the next chunk
  chunk_.has_schema.clear();
  chunk_.has_channel.clear();
  chunk_.message_index.clear();
}

void McapWriter::count_message(std::uint16_t channel_id, std::uint64_t log_time_ns) {
  mcap::Statistics& s = statistics_;
  if (s.message_count == 0 || log_time_ns < s.message_start_time)
    s.message_start_time = log_time_ns;
  if (s.message_count == 0 || log_time_ns > s.message_end_time) s.message_end_time = log_time_ns;
  ++s.message_count;
  ++s.channel_message_counts[channel_id];
}

// Spec "Summary Section" (records grouped by opcode; Channels before Statistics), "Summary
// Offset Section" (one Summary Offset per group), "Footer" and the closing magic.
Bytes McapWriter::summary_and_footer() {
  const std::uint64_t summary_start = offset_;
  Bytes out;
  std::vector<mcap::SummaryOffset> groups;
  const auto open_group = [&](Opcode opcode) {
    groups.push_back({static_cast<std::uint8_t>(opcode), summary_start + out.size(), 0});
  };
  const auto close_group = [&] {
    groups.back().group_length = summary_start + out.size() - groups.back().group_start;
  };
  open_group(Opcode::kSchema);
  for (const mcap::Schema& schema : schemas_)
    put_record(out, Opcode::kSchema, schema_content(schema));
  close_group();
  open_group(Opcode::kChannel);
  for (const mcap::Channel& channel : channels_) {
    put_record(out, Opcode::kChannel, channel_content(channel));
  }
  close_group();
  open_group(Opcode::kStatistics);
  statistics_.schema_count = static_cast<std::uint16_t>(schemas_.size());
  statistics_.channel_count = static_cast<std::uint32_t>(channels_.size());
  put_record(out, Opcode::kStatistics, statistics_content(statistics_));
  close_group();
  open_group(Opcode::kChunkIndex);
  for (const mcap::ChunkIndex& index : chunk_indexes_) {
    put_record(out, Opcode::kChunkIndex, chunk_index_content(index));
  }
  close_group();
  const std::uint64_t summary_offset_start = summary_start + out.size();
  for (const mcap::SummaryOffset& group : groups) {
    if (group.group_length > 0)
      put_record(out, Opcode::kSummaryOffset, summary_offset_content(group));
  }
  put_le(out, static_cast<std::uint8_t>(Opcode::kFooter));
  put_le(out, mcap::kFooterContentSize);
  put_le(out, summary_start);
  put_le(out, summary_offset_start);
  put_le(out, crc32_of(out));  // Spec "Footer": summary_crc covers everything before it
  out.insert(out.end(), std::begin(mcap::kMagic), std::end(mcap::kMagic));
  return out;
}

void McapWriter::put(const Bytes& bytes) {
  put(bytes.data(), bytes.size());
}

// put() keeps the CRC of every byte written: close() takes it as the data section's CRC just
// before it writes the Data End record.
void McapWriter::put(const std::uint8_t* data, std::size_t size) {
  data_section_crc_ = mcap::crc32_update(data_section_crc_, data, size);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd_, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) errno = EIO;  // write(2) of a non-empty buffer does not return 0
    if (n <= 0) fail("cannot write");
    done += static_cast<std::size_t>(n);
    offset_ += static_cast<std::uint64_t>(n);
  }
}

void McapWriter::sync() {
  // EINVAL/EROFS: a file that cannot be synced (a pipe, /dev/null); nothing to wait for.
  if (::fdatasync(fd_) != 0 && errno != EINVAL && errno != EROFS) fail("cannot sync");
}

void McapWriter::check_writable(const char* action) const {
  if (fd_ < 0) throw std::logic_error(path_ + ": " + action + " after close()");
  if (failed_)
    throw file_error(path_, std::string("cannot ") + action + ": an earlier write failed");
}

void McapWriter::fail(const std::string& what) {
  const std::string reason = errno != 0 ? std::strerror(errno) : "unknown error";
  failed_ = true;
  throw file_error(path_, what + ": " + reason);
}

}  // namespace uavslam::io
