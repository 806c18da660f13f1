#include "io/McapReader.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iomanip>
#include <sstream>

#include "io/McapCompression.hpp"

namespace uavslam::io {

namespace {

using Bytes = std::vector<std::uint8_t>;
using mcap::Opcode;

// Large enough to read a file quickly, small enough to be no burden.
constexpr std::uint64_t kPieceSize = 64 * 1024;
constexpr std::uint64_t kFooterRecordSize = mcap::kRecordPrefixSize + mcap::kFooterContentSize;
constexpr std::uint64_t kMagicSize = sizeof(mcap::kMagic);

// Spec "Fixed-width types": little-endian.
template <typename T>
T little_endian(const std::uint8_t* bytes) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) value |= std::uint64_t{bytes[i]} << (8 * i);
  return static_cast<T>(value);
}

std::string hex(std::uint32_t value) {
  std::ostringstream text;
  text << "0x" << std::hex << std::uppercase << std::setw(8) << std::setfill('0') << value;
  return text.str();
}

std::string at_byte(std::uint64_t offset) {
  return "at byte " + std::to_string(offset);
}

std::string too_short(std::uint8_t opcode, std::uint64_t at) {
  return mcap::opcode_name(opcode) + " record " + at_byte(at) + " is too short for its fields";
}

// The records a streaming read decodes; the spec says to skip the others (indexes,
// attachments, metadata, opcodes this reader does not know).
bool is_streamed(std::uint8_t opcode) {
  switch (static_cast<Opcode>(opcode)) {
    case Opcode::kHeader:
    case Opcode::kFooter:
    case Opcode::kDataEnd:
    case Opcode::kSchema:
    case Opcode::kChannel:
    case Opcode::kMessage:
    case Opcode::kChunk:
      return true;
    default:
      return false;
  }
}

bool is_magic(const Bytes& bytes) {
  return std::equal(bytes.begin(), bytes.end(), std::begin(mcap::kMagic));
}

// Reads the fields of one record's content in order (spec "Serialization"); every read first
// checks that its bytes are there and returns false when they are not.
class FieldCursor {
 public:
  FieldCursor(const std::uint8_t* data, std::uint64_t size) : data_(data), size_(size) {}
  explicit FieldCursor(const Bytes& bytes) : FieldCursor(bytes.data(), bytes.size()) {}

  std::uint64_t remaining() const { return size_ - at_; }
  std::uint64_t position() const { return at_; }

  template <typename T>
  bool read(T& value) {
    if (remaining() < sizeof(T)) return false;
    value = little_endian<T>(data_ + at_);
    at_ += sizeof(T);
    return true;
  }
  // `size` bytes, returned in place.
  bool read_span(std::uint64_t size, const std::uint8_t*& begin) {
    if (remaining() < size) return false;
    begin = data_ + at_;
    at_ += size;
    return true;
  }
  // Spec "String" and "uint32 length-prefixed Bytes".
  bool read_string(std::string& text) {
    std::uint32_t size = 0;
    const std::uint8_t* begin = nullptr;
    if (!read(size) || !read_span(size, begin)) return false;
    text.assign(reinterpret_cast<const char*>(begin), size);
    return true;
  }
  // Spec "Map<string, string>" and "Map<uint16, uint64>": a u32 byte length, then the entries.
  template <typename Key, typename Value>
  bool read_map(std::map<Key, Value>& map) {
    std::uint32_t size = 0;
    const std::uint8_t* begin = nullptr;
    if (!read(size) || !read_span(size, begin)) return false;
    FieldCursor entries(begin, size);
    while (entries.remaining() > 0) {
      Key key{};
      Value value{};
      if (!entries.read_entry(key) || !entries.read_entry(value)) return false;
      map[key] = std::move(value);
    }
    return true;
  }

 private:
  bool read_entry(std::string& text) { return read_string(text); }
  template <typename T>
  bool read_entry(T& value) {
    return read(value);
  }

  const std::uint8_t* data_;
  std::uint64_t size_;
  std::uint64_t at_ = 0;
};

// Spec "Header".
bool decode(FieldCursor& in, mcap::Header& header) {
  return in.read_string(header.profile) && in.read_string(header.library);
}

// Spec "Footer".
bool decode(FieldCursor& in, mcap::Footer& footer) {
  return in.read(footer.summary_start) && in.read(footer.summary_offset_start) &&
         in.read(footer.summary_crc);
}

// Spec "Schema".
bool decode(FieldCursor& in, mcap::Schema& schema) {
  return in.read(schema.id) && in.read_string(schema.name) && in.read_string(schema.encoding) &&
         in.read_string(schema.data);
}

// Spec "Channel".
bool decode(FieldCursor& in, mcap::Channel& channel) {
  return in.read(channel.id) && in.read(channel.schema_id) && in.read_string(channel.topic) &&
         in.read_string(channel.message_encoding) && in.read_map(channel.metadata);
}

// Spec "Message": the data is the rest of the record.
bool decode(FieldCursor& in, mcap::Message& message) {
  if (!in.read(message.channel_id) || !in.read(message.sequence) || !in.read(message.log_time) ||
      !in.read(message.publish_time)) {
    return false;
  }
  const std::uint64_t size = in.remaining();
  const std::uint8_t* begin = nullptr;
  in.read_span(size, begin);
  message.data.assign(begin, begin + size);
  return true;
}

// Spec "Chunk Index".
bool decode(FieldCursor& in, mcap::ChunkIndex& index) {
  return in.read(index.message_start_time) && in.read(index.message_end_time) &&
         in.read(index.chunk_start_offset) && in.read(index.chunk_length) &&
         in.read_map(index.message_index_offsets) && in.read(index.message_index_length) &&
         in.read_string(index.compression) && in.read(index.compressed_size) &&
         in.read(index.uncompressed_size);
}

// Spec "Statistics".
bool decode(FieldCursor& in, mcap::Statistics& s) {
  return in.read(s.message_count) && in.read(s.schema_count) && in.read(s.channel_count) &&
         in.read(s.attachment_count) && in.read(s.metadata_count) && in.read(s.chunk_count) &&
         in.read(s.message_start_time) && in.read(s.message_end_time) &&
         in.read_map(s.channel_message_counts);
}

// Spec "Chunk": the fields, and the records field in place.
struct ChunkFields {
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;
  std::string compression;
  std::uint64_t records_size = 0;
  const std::uint8_t* records = nullptr;
};

bool decode(FieldCursor& in, ChunkFields& chunk) {
  return in.read(chunk.message_start_time) && in.read(chunk.message_end_time) &&
         in.read(chunk.uncompressed_size) && in.read(chunk.uncompressed_crc) &&
         in.read_string(chunk.compression) && in.read(chunk.records_size) &&
         in.read_span(chunk.records_size, chunk.records);
}

// Where the Schema, Channel and Message records read go.
struct MessageStore {
  std::map<std::uint16_t, mcap::Schema>& schemas;
  std::map<std::uint16_t, mcap::Channel>& channels;
  std::deque<mcap::Message>& messages;
};

// Takes one Schema, Channel or Message record (in the data section or in a chunk) whose content
// is `content`, found at file offset `at`; other records are none of its business. Returns ""
// or the problem.
std::string take_record(std::uint8_t opcode, std::uint64_t at, FieldCursor content,
                        MessageStore& store) {
  switch (static_cast<Opcode>(opcode)) {
    case Opcode::kSchema: {
      mcap::Schema schema;
      if (!decode(content, schema)) return too_short(opcode, at);
      if (schema.id != 0) store.schemas[schema.id] = std::move(schema);  // spec: ignore id 0
      return "";
    }
    case Opcode::kChannel: {
      mcap::Channel channel;
      if (!decode(content, channel)) return too_short(opcode, at);
      store.channels[channel.id] = std::move(channel);
      return "";
    }
    case Opcode::kMessage: {
      mcap::Message message;
      if (!decode(content, message)) return too_short(opcode, at);
      // Spec "Channel": a Channel record comes before any message on it.
      if (store.channels.count(message.channel_id) == 0) {
        return "Message " + at_byte(at) + " is on channel " + std::to_string(message.channel_id) +
               ", which no Channel record before it declares";
      }
      store.messages.push_back(std::move(message));
      return "";
    }
    default:
      return "";
  }
}

// Takes the records of an uncompressed chunk, which start at file offset `at`.
std::string take_chunk_records(std::uint64_t at, FieldCursor records, MessageStore& store) {
  while (records.remaining() > 0) {
    const std::uint64_t record_at = at + records.position();
    std::uint8_t opcode = 0;
    std::uint64_t length = 0;
    const std::uint8_t* content = nullptr;
    if (!records.read(opcode) || !records.read(length)) {
      return "record " + at_byte(record_at) + " overruns its Chunk";
    }
    if (!records.read_span(length, content)) {
      return mcap::opcode_name(opcode) + " record " + at_byte(record_at) + " of " +
             std::to_string(length) + " bytes overruns its Chunk";
    }
    std::string problem = take_record(opcode, record_at, FieldCursor(content, length), store);
    if (!problem.empty()) return problem;
  }
  return "";
}

// Checks the CRC of a chunk's (decompressed) records; "" or the problem.
std::string checked_records(std::uint64_t at, const ChunkFields& chunk, const std::uint8_t* records,
                            std::uint64_t size) {
  const std::uint32_t crc = mcap::crc32_update(0, records, size);
  if (chunk.uncompressed_crc != 0 && crc != chunk.uncompressed_crc) {
    return "chunk CRC mismatch " + at_byte(at) + " (the Chunk says " + hex(chunk.uncompressed_crc) +
           ", its " + (chunk.compression.empty() ? "" : "decompressed ") + "records give " +
           hex(crc) + ")";
  }
  return "";
}

// Takes the Chunk record found at file offset `at` whose content is `content`: decompresses its
// records if they are compressed ("lz4", "zstd"), checks their length and CRC and takes their
// Schema, Channel and Message records. A chunk of another compression is noted in `skipped`.
// Returns "" or the problem (the messages of earlier records are taken; a chunk whose records
// cannot be checked gives none).
std::string take_chunk(std::uint64_t at, const Bytes& content, MessageStore& store,
                       std::vector<std::string>& skipped) {
  FieldCursor cursor(content);
  ChunkFields chunk;
  if (!decode(cursor, chunk)) return too_short(static_cast<std::uint8_t>(Opcode::kChunk), at);
  const std::uint64_t records_at =
      at + mcap::kRecordPrefixSize + static_cast<std::uint64_t>(chunk.records - content.data());
  if (chunk.compression.empty()) {
    if (chunk.uncompressed_size != chunk.records_size) {
      return "Chunk " + at_byte(at) + " says its records have " +
             std::to_string(chunk.uncompressed_size) + " bytes, but has " +
             std::to_string(chunk.records_size);
    }
    std::string problem = checked_records(at, chunk, chunk.records, chunk.records_size);
    if (!problem.empty()) return problem;
    return take_chunk_records(records_at, FieldCursor(chunk.records, chunk.records_size), store);
  }
  if (!can_decompress_chunk(chunk.compression)) {
    skipped.push_back("Chunk " + at_byte(at) + ": compression \"" + chunk.compression +
                      "\" is not supported, its messages were skipped");
    return "";
  }
  Bytes records;
  std::string problem = decompress_chunk_records(
      chunk.compression, chunk.records, chunk.records_size, chunk.uncompressed_size, records);
  if (!problem.empty()) return "Chunk " + at_byte(at) + " (" + chunk.compression + "): " + problem;
  problem = checked_records(at, chunk, records.data(), records.size());
  if (!problem.empty()) return problem;
  problem = take_chunk_records(0, FieldCursor(records), store);
  if (!problem.empty()) {
    return "Chunk " + at_byte(at) + " (" + chunk.compression +
           "), in its decompressed records: " + problem;
  }
  return "";
}

// What the summary's records go into (spec "Summary Section").
struct SummaryStore {
  MessageStore records;  // Schema and Channel records
  std::optional<mcap::Statistics>& statistics;
  std::vector<mcap::ChunkIndex>& chunk_indexes;
  std::uint64_t summary_start;  // chunks lie before it
};

// Takes one record of the summary found at file offset `at`; false when it is malformed or
// points outside the data section.
bool take_summary_record(std::uint8_t opcode, std::uint64_t at, FieldCursor fields,
                         SummaryStore& store) {
  if (opcode == static_cast<std::uint8_t>(Opcode::kStatistics)) {
    return decode(fields, store.statistics.emplace());
  }
  if (opcode == static_cast<std::uint8_t>(Opcode::kChunkIndex)) {
    mcap::ChunkIndex index;
    if (!decode(fields, index) || index.chunk_length < mcap::kRecordPrefixSize ||
        index.chunk_length > store.summary_start ||
        index.chunk_start_offset > store.summary_start - index.chunk_length) {
      return false;
    }
    store.chunk_indexes.push_back(std::move(index));
    return true;
  }
  return take_record(opcode, at, fields, store.records).empty();
}

}  // namespace

McapFile::McapFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw file_error(path, std::string("cannot open: ") + std::strerror(errno));
  struct stat status {};
  if (::fstat(fd_, &status) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(fd_);
    throw file_error(path, "cannot open: " + reason);
  }
  size_ = status.st_size > 0 ? static_cast<std::uint64_t>(status.st_size) : 0;
}

McapFile::~McapFile() {
  ::close(fd_);
}

bool McapFile::read(std::uint64_t offset, std::uint64_t size, Bytes& out,
                    std::string& error) const {
  if (offset > size_ || size > size_ - offset) {
    error = "the file ends at byte " + std::to_string(size_);
    return false;
  }
  out.resize(size);
  std::uint64_t done = 0;
  while (done < size) {
    const ssize_t n =
        ::pread(fd_, out.data() + done, size - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = n == 0 ? "the file became shorter while it was read"
                     : std::string("cannot read: ") + std::strerror(errno);
      return false;
    }
    done += static_cast<std::uint64_t>(n);
  }
  return true;
}

bool McapFile::crc32(std::uint64_t begin, std::uint64_t end, std::uint32_t& crc,
                     std::string& error) const {
  crc = 0;
  Bytes piece;
  for (std::uint64_t at = begin; at < end; at += piece.size()) {
    if (!read(at, std::min(kPieceSize, end - at), piece, error)) return false;
    crc = mcap::crc32_update(crc, piece.data(), piece.size());
  }
  return true;
}

McapStreamReader::McapStreamReader(const std::string& path) : file_(path) {
  read_magic();
}

bool McapStreamReader::next(mcap::Message& message) {
  for (;;) {
    if (!pending_.empty()) {
      message = std::move(pending_.front());
      pending_.pop_front();
      return true;
    }
    if (finished_) return false;
    read_record();
  }
}

// Spec "Magic".
void McapStreamReader::read_magic() {
  if (file_.size() == 0) return stop(0, "not an MCAP file: the file is empty");
  Bytes magic;
  const std::uint64_t size = std::min(kMagicSize, file_.size());
  if (!read_bytes(size, magic)) return;
  if (!is_magic(magic)) return stop(0, "not an MCAP file: bad magic");
  if (size < kMagicSize) return stop(0, "truncated inside the opening magic");
}

// One record of the data or summary section (spec "Records").
void McapStreamReader::read_record() {
  const std::uint64_t at = offset_;
  const std::uint32_t crc_before = data_crc_;
  std::uint8_t opcode = 0;
  std::uint64_t length = 0;
  if (!read_prefix(opcode, length)) return;
  if (!header_seen_ && opcode != static_cast<std::uint8_t>(Opcode::kHeader)) {
    return stop(at,
                "expected a Header record " + at_byte(at) + ", found " + mcap::opcode_name(opcode));
  }
  // After the Data End, the Schemas and Channels are the summary's copies: not needed here.
  if (!is_streamed(opcode) ||
      (data_end_seen_ && opcode != static_cast<std::uint8_t>(Opcode::kFooter))) {
    skip_bytes(length);
    return;
  }
  Bytes content;
  if (!read_bytes(length, content)) return;
  switch (static_cast<Opcode>(opcode)) {
    case Opcode::kHeader:
      return on_header(at, content);
    case Opcode::kDataEnd:
      return on_data_end(at, crc_before, content);
    case Opcode::kFooter:
      return on_footer(at, content);
    default:
      return on_data_record(opcode, at, content);
  }
}

// A record's opcode and content length, when the file holds the whole record.
bool McapStreamReader::read_prefix(std::uint8_t& opcode, std::uint64_t& length) {
  const std::uint64_t at = offset_;
  if (at == file_.size()) {
    stop(at, data_end_seen_ ? "the file ends " + at_byte(at) + " without a Footer"
                            : "the file ends " + at_byte(at) +
                                  " without a Data End record (cut short, or not closed yet)");
    return false;
  }
  if (file_.size() - at < mcap::kRecordPrefixSize) {
    stop(at, "truncated inside a record's opcode and length " + at_byte(at));
    return false;
  }
  Bytes prefix;
  if (!read_bytes(mcap::kRecordPrefixSize, prefix)) return false;
  opcode = prefix[0];
  length = little_endian<std::uint64_t>(prefix.data() + 1);
  if (length > file_.size() - offset_) {
    stop(at, "truncated inside a " + mcap::opcode_name(opcode) + " record " + at_byte(at) +
                 " (its length says " + std::to_string(length) + " bytes, " +
                 std::to_string(file_.size() - offset_) + " remain)");
    return false;
  }
  return true;
}

bool McapStreamReader::read_bytes(std::uint64_t size, Bytes& out) {
  std::string error;
  if (!file_.read(offset_, size, out, error)) {
    stop(offset_, error);
    return false;
  }
  if (!data_end_seen_) data_crc_ = mcap::crc32_update(data_crc_, out.data(), out.size());
  offset_ += size;
  return true;
}

// Reads past `size` bytes (already known to be in the file); the data section's CRC needs them.
bool McapStreamReader::skip_bytes(std::uint64_t size) {
  if (data_end_seen_) {
    offset_ += size;
    return true;
  }
  Bytes piece;
  for (std::uint64_t left = size; left > 0; left -= piece.size()) {
    if (!read_bytes(std::min(kPieceSize, left), piece)) return false;
  }
  return true;
}

// Spec "Header": the first record. A second one is not ours to judge; it is skipped.
void McapStreamReader::on_header(std::uint64_t at, const Bytes& content) {
  if (header_seen_) return;
  FieldCursor cursor(content);
  if (!decode(cursor, header_)) {
    return stop(at, too_short(static_cast<std::uint8_t>(Opcode::kHeader), at));
  }
  header_seen_ = true;
}

// Spec "Data End": its CRC covers every byte of the file before it.
void McapStreamReader::on_data_end(std::uint64_t at, std::uint32_t crc_before,
                                   const Bytes& content) {
  FieldCursor cursor(content);
  std::uint32_t crc = 0;
  if (!cursor.read(crc))
    return stop(at, too_short(static_cast<std::uint8_t>(Opcode::kDataEnd), at));
  if (crc != 0 && crc != crc_before) {
    return stop(at, "data section CRC mismatch " + at_byte(at) + " (the Data End says " + hex(crc) +
                        ", the bytes before it give " + hex(crc_before) + ")");
  }
  data_end_seen_ = true;
  data_end_end_ = offset_;
}

// Spec "Footer": the last record; its CRC covers the summary sections and its own first fields.
void McapStreamReader::on_footer(std::uint64_t at, const Bytes& content) {
  if (content.size() != mcap::kFooterContentSize) {
    return stop(at, "Footer " + at_byte(at) + " has " + std::to_string(content.size()) +
                        " bytes of content instead of " + std::to_string(mcap::kFooterContentSize));
  }
  if (!data_end_seen_) return stop(at, "Footer " + at_byte(at) + " without a Data End record");
  FieldCursor cursor(content);
  mcap::Footer footer;
  decode(cursor, footer);
  if (footer.summary_crc != 0) {
    const std::uint64_t begin = footer.summary_start != 0 ? footer.summary_start : data_end_end_;
    if (begin < data_end_end_ || begin > at) {
      return stop(at, "Footer " + at_byte(at) + ": summary_start " + std::to_string(begin) +
                          " is not in the summary section");
    }
    std::uint32_t crc = 0;
    std::string error;
    if (!file_.crc32(begin, at + mcap::kRecordPrefixSize + 8 + 8, crc, error)) {
      return stop(at, error);
    }
    if (crc != footer.summary_crc) {
      return stop(at, "summary CRC mismatch " + at_byte(at) + " (the Footer says " +
                          hex(footer.summary_crc) + ", the summary gives " + hex(crc) + ")");
    }
  }
  check_closing_magic(offset_);
}

// Spec "Magic": the file ends with it.
void McapStreamReader::check_closing_magic(std::uint64_t at) {
  Bytes magic;
  const std::uint64_t size = std::min(kMagicSize, file_.size() - at);
  if (!read_bytes(size, magic)) return;
  if (!is_magic(magic)) return stop(at, "bad closing magic " + at_byte(at));
  if (size < kMagicSize) return stop(at, "truncated inside the closing magic " + at_byte(at));
  if (offset_ != file_.size()) {
    return stop(offset_, std::to_string(file_.size() - offset_) +
                             " bytes after the closing magic " + at_byte(offset_));
  }
  finished_ = true;
  report_.complete = true;
  report_.stopped_at = offset_;
}

void McapStreamReader::on_data_record(std::uint8_t opcode, std::uint64_t at, const Bytes& content) {
  MessageStore store{schemas_, channels_, pending_};
  const std::string problem = opcode == static_cast<std::uint8_t>(Opcode::kChunk)
                                  ? take_chunk(at, content, store, report_.skipped)
                                  : take_record(opcode, at, FieldCursor(content), store);
  if (!problem.empty()) stop(at, problem);
}

void McapStreamReader::stop(std::uint64_t at, const std::string& problem) {
  finished_ = true;
  report_.stopped_at = at;
  report_.problem = problem;
}

McapIndexedReader::McapIndexedReader(const std::string& path) : file_(path) {
  read_header();
  if (load_summary()) return;
  schemas_.clear();
  channels_.clear();
  statistics_.reset();
  chunk_indexes_.clear();
}

// Spec "Header": right after the opening magic; read for header() only.
void McapIndexedReader::read_header() {
  Bytes prefix;
  Bytes content;
  std::string error;
  if (!file_.read(kMagicSize, mcap::kRecordPrefixSize, prefix, error) ||
      prefix[0] != static_cast<std::uint8_t>(Opcode::kHeader) ||
      !file_.read(kMagicSize + mcap::kRecordPrefixSize,
                  little_endian<std::uint64_t>(prefix.data() + 1), content, error)) {
    return;
  }
  FieldCursor cursor(content);
  decode(cursor, header_);
}

// Spec "Footer" and "Summary Section": the Footer is the last record before the closing magic
// and says where the summary is.
bool McapIndexedReader::load_summary() {
  const std::uint64_t size = file_.size();
  const auto fail = [this](const std::string& problem) {
    summary_problem_ = problem;
    return false;
  };
  Bytes bytes;
  std::string error;
  if (!file_.read(0, kMagicSize, bytes, error) || !is_magic(bytes)) {
    return fail("not an MCAP file: bad magic");
  }
  if (size < 2 * kMagicSize + kFooterRecordSize ||
      !file_.read(size - kMagicSize, kMagicSize, bytes, error) || !is_magic(bytes)) {
    return fail("no closing magic: the file was cut short or not closed");
  }
  const std::uint64_t footer_at = size - kMagicSize - kFooterRecordSize;
  if (!file_.read(footer_at, kFooterRecordSize, bytes, error) ||
      bytes[0] != static_cast<std::uint8_t>(Opcode::kFooter) ||
      little_endian<std::uint64_t>(bytes.data() + 1) != mcap::kFooterContentSize) {
    return fail("no Footer record " + at_byte(footer_at));
  }
  FieldCursor cursor(bytes.data() + mcap::kRecordPrefixSize, mcap::kFooterContentSize);
  mcap::Footer footer;
  decode(cursor, footer);
  if (footer.summary_start == 0) return fail("the file has no summary section");
  const std::uint64_t summary_end =
      footer.summary_offset_start != 0 ? footer.summary_offset_start : footer_at;
  if (footer.summary_start < kMagicSize || footer.summary_start > summary_end ||
      summary_end > footer_at) {
    return fail("Footer " + at_byte(footer_at) + " points outside the file's summary");
  }
  if (footer.summary_crc != 0) {
    std::uint32_t crc = 0;
    if (!file_.crc32(footer.summary_start, footer_at + mcap::kRecordPrefixSize + 8 + 8, crc,
                     error)) {
      return fail(error);
    }
    if (crc != footer.summary_crc) return fail("summary CRC mismatch " + at_byte(footer_at));
  }
  return load_summary_records(footer.summary_start, summary_end);
}

// Spec "Summary Section": Schema, Channel, Statistics and Chunk Index records are used, the
// others skipped.
bool McapIndexedReader::load_summary_records(std::uint64_t begin, std::uint64_t end) {
  Bytes summary;
  std::string error;
  if (!file_.read(begin, end - begin, summary, error)) {
    summary_problem_ = error;
    return false;
  }
  FieldCursor records(summary);
  std::deque<mcap::Message> no_messages;
  SummaryStore store{{schemas_, channels_, no_messages}, statistics_, chunk_indexes_, begin};
  while (records.remaining() > 0) {
    const std::uint64_t at = begin + records.position();
    std::uint8_t opcode = 0;
    std::uint64_t length = 0;
    const std::uint8_t* content = nullptr;
    if (!records.read(opcode) || !records.read(length) || !records.read_span(length, content)) {
      summary_problem_ = "summary record " + at_byte(at) + " overruns the summary section";
      return false;
    }
    if (!take_summary_record(opcode, at, FieldCursor(content, length), store)) {
      summary_problem_ = mcap::opcode_name(opcode) + " record " + at_byte(at) + " is malformed";
      return false;
    }
  }
  std::sort(chunk_indexes_.begin(), chunk_indexes_.end(),
            [](const mcap::ChunkIndex& a, const mcap::ChunkIndex& b) {
              return a.chunk_start_offset < b.chunk_start_offset;
            });
  return true;
}

McapReadReport McapIndexedReader::read_messages(
    std::uint64_t start_time_ns, const std::function<bool(const mcap::Message&)>& visit) {
  if (!has_summary()) return stream_messages(start_time_ns, visit);
  McapReadReport report;
  for (const mcap::ChunkIndex& index : chunk_indexes_) {
    if (index.message_end_time < start_time_ns) continue;
    std::deque<mcap::Message> messages;
    const bool ok = read_chunk(index, messages, report);
    for (const mcap::Message& message : messages) {
      if (message.log_time >= start_time_ns && !visit(message)) {
        report.complete = ok;
        return report;
      }
    }
    if (!ok) return report;
  }
  report.complete = true;
  report.stopped_at = file_.size();
  return report;
}

McapReadReport McapIndexedReader::stream_messages(
    std::uint64_t start_time_ns, const std::function<bool(const mcap::Message&)>& visit) {
  McapStreamReader reader(file_.path());
  mcap::Message message;
  bool stopped_by_visit = false;
  while (!stopped_by_visit && reader.next(message)) {
    stopped_by_visit = message.log_time >= start_time_ns && !visit(message);
  }
  schemas_ = reader.schemas();
  channels_ = reader.channels();
  header_ = reader.header();
  McapReadReport report = reader.report();
  if (stopped_by_visit) report.complete = report.problem.empty();
  return report;
}

// Reads the Chunk record a Chunk Index points at; false (report filled in) when it is not there
// or damaged. The messages before the damage are in `messages`.
bool McapIndexedReader::read_chunk(const mcap::ChunkIndex& index,
                                   std::deque<mcap::Message>& messages, McapReadReport& report) {
  const std::uint64_t at = index.chunk_start_offset;
  const auto fail = [&](const std::string& problem) {
    report.problem = problem;
    report.stopped_at = at;
    return false;
  };
  Bytes bytes;
  std::string error;
  if (!file_.read(at, mcap::kRecordPrefixSize, bytes, error) ||
      bytes[0] != static_cast<std::uint8_t>(Opcode::kChunk) ||
      little_endian<std::uint64_t>(bytes.data() + 1) !=
          index.chunk_length - mcap::kRecordPrefixSize) {
    return fail("a Chunk Index points " + at_byte(at) + ", where there is no Chunk of " +
                std::to_string(index.chunk_length) + " bytes");
  }
  if (!file_.read(at + mcap::kRecordPrefixSize, index.chunk_length - mcap::kRecordPrefixSize, bytes,
                  error)) {
    return fail(error);
  }
  MessageStore store{schemas_, channels_, messages};
  const std::string problem = take_chunk(at, bytes, store, report.skipped);
  return problem.empty() || fail(problem);
}

}  // namespace uavslam::io
