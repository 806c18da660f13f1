// Writes an MCAP file (see io/Mcap.hpp): messages in Chunks (uncompressed, or each compressed
// whole with lz4 or zstd: io/McapCompression.hpp), each followed by its
// Message Index records, and on close() a Data End record, the summary (Schemas, Channels,
// Statistics, Chunk Indexes), the Summary Offsets and the Footer. Every CRC the spec allows is
// filled in.
//
// A recorder that is killed leaves a file without summary: every chunk written by flush() (or
// because it reached its target size) is whole on disk, and McapStreamReader reads it back.
// Each chunk repeats the Schema and Channel records of its messages, so any chunk can be
// decoded on its own, as the spec recommends.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/FileError.hpp"
#include "io/Mcap.hpp"
#include "io/McapCompression.hpp"

namespace uavslam::io {

struct McapWriterOptions {
  // A chunk is closed once its records reach this many bytes (a single larger message makes a
  // chunk of its own).
  std::size_t chunk_size = 1024 * 1024;
  // How each chunk's records are compressed. kNone by default: on the demo flight's recording
  // zstd saves a third of the size (lz4 a quarter) for little CPU, a gain that does not yet
  // justify changing what every existing recording looks like (docs/recordings.md).
  McapCompression compression = McapCompression::kNone;
  // flush() also waits until the OS has the data on the storage device (fdatasync), so that
  // a power cut loses nothing flushed. close() always does.
  bool sync_on_flush = false;
  std::string profile;              // Header profile; "" is "no well-known profile"
  std::string library = "uavslam";  // Header library
};

class McapWriter {
 public:
  // Creates (or truncates) path and writes the magic and the Header. Throws FileError naming
  // the path and the system's reason when it cannot.
  explicit McapWriter(const std::string& path, McapWriterOptions options = {});
  // Closes like close(), but cannot report an error.
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  // Registers a schema and returns its id (from 1); the same three values again return the same
  // id. For our DDS types: name "uavslam::msg::LaserScan", encoding "omgidl", data the IDL text.
  std::uint16_t add_schema(const std::string& name, const std::string& encoding,
                           const std::string& data);
  // Registers a channel of a registered schema (0: none) and returns its id (from 1); the same
  // values again return the same id. std::invalid_argument for an unknown schema id.
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic,
                            const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  // Appends one message to the open chunk, closing the chunk when it is full.
  // std::invalid_argument for an unknown channel id; FileError when the file cannot be written.
  void write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns,
             std::uint64_t publish_time_ns, const std::uint8_t* data, std::size_t size);
  // Closes the open chunk and hands everything to the OS, so that the file holds every message
  // written so far even if this process dies next. FileError when it cannot be written.
  void flush();
  // Writes the rest of the file (Data End, summary, Footer, magic), syncs and closes it.
  // FileError when that fails; a second call does nothing. After a FileError from any call the
  // file is left as it is (McapStreamReader reads what is whole) and close() only releases it;
  // write() and flush() then throw FileError again.
  void close();

  // The file's size if the open chunk were flushed now uncompressed (the summary close() adds
  // not counted; a compressed chunk comes out smaller): what a recorder compares with its
  // roll-over size.
  std::uint64_t bytes_written() const;
  const std::string& path() const { return path_; }

 private:
  struct OpenChunk {
    std::vector<std::uint8_t> records;
    std::uint64_t message_start_time = 0;
    std::uint64_t message_end_time = 0;
    std::vector<bool> has_schema;   // by schema id: its Schema record is in this chunk
    std::vector<bool> has_channel;  // by channel id: its Channel record is in this chunk
    // channel id -> (log_time, offset of the Message record in `records`)
    std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> message_index;
  };

  void add_to_chunk(const mcap::Channel& channel);
  void close_chunk();
  void clear_chunk();
  void count_message(std::uint16_t channel_id, std::uint64_t log_time_ns);
  std::vector<std::uint8_t> summary_and_footer();
  void put(const std::vector<std::uint8_t>& bytes);
  void put(const std::uint8_t* data, std::size_t size);
  void sync();
  void check_writable(const char* action) const;
  [[noreturn]] void fail(const std::string& what);

  std::string path_;
  McapWriterOptions options_;
  int fd_ = -1;
  bool failed_ = false;                  // a write failed: the file is left as it is
  std::uint64_t offset_ = 0;             // bytes handed to the file so far
  std::uint32_t data_section_crc_ = 0;   // of every byte written so far
  std::vector<mcap::Schema> schemas_;    // index id - 1
  std::vector<mcap::Channel> channels_;  // index id - 1
  OpenChunk chunk_;
  std::vector<mcap::ChunkIndex> chunk_indexes_;
  mcap::Statistics statistics_;
};

}  // namespace uavslam::io
