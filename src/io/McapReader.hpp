// Reads MCAP files (see io/Mcap.hpp), as McapWriter writes them and as other writers may.
//
// McapStreamReader walks a file record by record from its start and needs no summary: it reads
// what a recorder that was killed left behind. McapIndexedReader loads the summary through the
// Footer and seeks to the chunks it needs, and falls back to a streaming read when the file has
// no (usable) summary.
//
// Neither throws on bad content: they return every whole message before the damage and report
// where and why they stopped. Every length is checked against the bytes that are really there
// before anything is allocated, so a corrupted or hostile file cannot make them allocate more
// than the file's size. Chunks compressed with "lz4" or "zstd" are decompressed (io/
// McapCompression.hpp): their uncompressed_size is only a claim, so the output grows with what
// the data really decodes to, a claim over 256 MiB or over what the format can make of the
// compressed bytes is refused, and a chunk that decodes to another length or CRC stops the read
// at the Chunk's offset, like a damaged uncompressed chunk (none of its messages are returned,
// all before it are). Chunks of any other compression are skipped and reported. Only a file
// that cannot be opened throws (FileError).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/FileError.hpp"
#include "io/Mcap.hpp"

namespace uavslam::io {

struct McapReadReport {
  // Read to its end: for a streaming read the Footer and the closing magic, for an indexed read
  // every chunk asked for; every CRC present matched.
  bool complete = false;
  // Byte offset where reading stopped: the start of the damaged record, or the file's size.
  std::uint64_t stopped_at = 0;
  // Why reading stopped early, e.g. "truncated inside a Chunk record at byte 123456"; empty
  // when complete.
  std::string problem;
  // Records that were read past without their messages: chunks of an unknown compression.
  std::vector<std::string> skipped;
};

// The open file, read at offsets; every read is checked against the file's size.
class McapFile {
 public:
  // Throws FileError naming the path and the system's reason when it cannot be opened.
  explicit McapFile(const std::string& path);
  ~McapFile();
  McapFile(const McapFile&) = delete;
  McapFile& operator=(const McapFile&) = delete;

  std::uint64_t size() const { return size_; }
  const std::string& path() const { return path_; }
  // Reads `size` bytes at `offset` into `out`; false with `error` set when the file is shorter or
  // the system fails.
  bool read(std::uint64_t offset, std::uint64_t size, std::vector<std::uint8_t>& out,
            std::string& error) const;
  // CRC-32 of the bytes [begin, end), read in pieces; false with `error` set on failure.
  bool crc32(std::uint64_t begin, std::uint64_t end, std::uint32_t& crc, std::string& error) const;

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

class McapStreamReader {
 public:
  // Opens path (FileError when it cannot) and reads the magic and the Header.
  explicit McapStreamReader(const std::string& path);

  // The next message in file order (inside chunks too); false at the end of the file or where
  // it is damaged (see report()).
  bool next(mcap::Message& message);

  const mcap::Header& header() const { return header_; }
  // The Schema and Channel records met so far.
  const std::map<std::uint16_t, mcap::Schema>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, mcap::Channel>& channels() const { return channels_; }
  const McapReadReport& report() const { return report_; }

 private:
  void read_record();
  bool read_prefix(std::uint8_t& opcode, std::uint64_t& length);
  bool read_bytes(std::uint64_t size, std::vector<std::uint8_t>& out);
  bool skip_bytes(std::uint64_t size);
  void read_magic();
  void on_header(std::uint64_t at, const std::vector<std::uint8_t>& content);
  void on_data_end(std::uint64_t at, std::uint32_t crc_before,
                   const std::vector<std::uint8_t>& content);
  void on_footer(std::uint64_t at, const std::vector<std::uint8_t>& content);
  void check_closing_magic(std::uint64_t at);
  void on_data_record(std::uint8_t opcode, std::uint64_t at,
                      const std::vector<std::uint8_t>& content);
  void stop(std::uint64_t at, const std::string& problem);

  McapFile file_;
  std::uint64_t offset_ = 0;
  std::uint32_t data_crc_ = 0;  // of the bytes read before the Data End record
  bool header_seen_ = false;
  bool data_end_seen_ = false;
  std::uint64_t data_end_end_ = 0;  // offset just past the Data End record
  bool finished_ = false;
  mcap::Header header_;
  std::map<std::uint16_t, mcap::Schema> schemas_;
  std::map<std::uint16_t, mcap::Channel> channels_;
  std::deque<mcap::Message> pending_;  // the decoded messages of the current chunk
  McapReadReport report_;
};

class McapIndexedReader {
 public:
  // Opens path (FileError when it cannot) and loads its summary if it has a usable one.
  explicit McapIndexedReader(const std::string& path);

  bool has_summary() const { return summary_problem_.empty(); }
  // Why the summary cannot be used (e.g. "no Footer: the file ends with ..."); empty if it can.
  const std::string& summary_problem() const { return summary_problem_; }
  const mcap::Header& header() const { return header_; }
  // From the summary; after read_messages() on a file without one, those the streaming read met.
  const std::map<std::uint16_t, mcap::Schema>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, mcap::Channel>& channels() const { return channels_; }
  const std::optional<mcap::Statistics>& statistics() const { return statistics_; }
  const std::vector<mcap::ChunkIndex>& chunk_indexes() const { return chunk_indexes_; }

  // Calls visit(message) for every message with log_time >= start_time_ns, in file order, until
  // visit returns false. With a summary it reads only the chunks whose Chunk Index says they end
  // at or after start_time_ns; without one it streams the whole file.
  McapReadReport read_messages(std::uint64_t start_time_ns,
                               const std::function<bool(const mcap::Message&)>& visit);

 private:
  void read_header();
  bool load_summary();
  bool load_summary_records(std::uint64_t begin, std::uint64_t end);
  McapReadReport stream_messages(std::uint64_t start_time_ns,
                                 const std::function<bool(const mcap::Message&)>& visit);
  bool read_chunk(const mcap::ChunkIndex& index, std::deque<mcap::Message>& messages,
                  McapReadReport& report);

  McapFile file_;
  std::string summary_problem_;
  mcap::Header header_;
  std::map<std::uint16_t, mcap::Schema> schemas_;
  std::map<std::uint16_t, mcap::Channel> channels_;
  std::optional<mcap::Statistics> statistics_;
  std::vector<mcap::ChunkIndex> chunk_indexes_;
};

}  // namespace uavslam::io
