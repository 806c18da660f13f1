// Sample logs: DDS samples as the recorder received them, in a small documented binary format
// (.uavlog) that stands in until the logs move to MCAP. Bytes in, bytes out: this file knows
// nothing of DDS; a payload is a sample's CDR bytes exactly as the fastddsgen PubSubType's
// serialize() writes them (encapsulation header included), so PubSubType::deserialize reads it.
//
// Format, version 1. Every integer is little-endian; strings are UTF-8 without terminator.
//
//   file    := header record*
//   header  := magic "UAVSLOG\0" (8 bytes), version u32 (= 1)
//   record  := kind u8, body_length u32, body (body_length bytes)
//   kind 1, channel: id u16, topic_length u16, topic, type_length u16, type
//                    (declares a channel before its first sample; the type is the DDS type
//                    name, e.g. "uavslam::msg::LaserScan")
//   kind 2, sample:  channel u16, receive_time_ns i64, source_time_ns i64, payload
//                    (payload_length = body_length - 18; receive time: the recorder's system
//                    clock when the sample arrived; source time: the writer's DDS source
//                    timestamp; both nanoseconds since the Unix epoch)
//
// Records of other kinds are skipped by readers of this version (room for indexes or metadata).
// A record is written whole or the file ends inside it: a recorder that is killed leaves a
// truncated tail, and recover_sample_log() returns every complete record before it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "io/FileError.hpp"

namespace uavslam::io {

inline constexpr char kSampleLogMagic[8] = {'U', 'A', 'V', 'S', 'L', 'O', 'G', '\0'};
inline constexpr std::uint32_t kSampleLogVersion = 1;

struct LogChannel {
  std::uint16_t id = 0;
  std::string topic;
  std::string type;
};

struct LogSample {
  std::uint16_t channel = 0;
  std::int64_t receive_time_ns = 0;
  std::int64_t source_time_ns = 0;
  std::vector<std::uint8_t> payload;
};

class SampleLogWriter {
 public:
  // Creates (or truncates) path and writes the header. Throws FileError naming the path and the
  // system's reason when it cannot be written. The header and channel records are flushed at
  // once; samples are buffered until flush().
  explicit SampleLogWriter(const std::string& path);

  // Declares a channel and returns its id; the same topic and type again return the same id.
  std::uint16_t add_channel(const std::string& topic, const std::string& type);
  // Appends one sample of a declared channel (std::invalid_argument otherwise).
  void write(std::uint16_t channel, std::int64_t receive_time_ns, std::int64_t source_time_ns,
             const std::uint8_t* payload, std::size_t size);
  // Pushes what is buffered to the file, so a reader sees every record written so far.
  void flush();
  // Flushes and closes; throws FileError if the data could not be written. The destructor closes
  // too, but cannot report an error.
  void close();

  std::uint64_t bytes_written() const { return bytes_; }
  const std::string& path() const { return path_; }

 private:
  void put(const void* data, std::size_t size);
  void check();

  std::string path_;
  std::ofstream out_;
  std::vector<LogChannel> channels_;
  std::uint64_t bytes_ = 0;
};

// Reads a sample log record by record. Errors are FileError "<path>: byte <offset>: <problem>",
// the offset being where the damaged record (or header) starts.
class SampleLogReader {
 public:
  // Opens path and checks the header ("not a uavslam sample log", "unsupported version").
  explicit SampleLogReader(const std::string& path);

  // The next sample (channel records are taken into channels() on the way); false at the end of a
  // complete file. Throws FileError on a truncated or corrupt record (a sample of an undeclared
  // channel, a body too short for its kind, an implausible length).
  bool next(LogSample& sample);

  const std::vector<LogChannel>& channels() const { return channels_; }
  // The channel `id` of channels(); throws std::out_of_range when it was not declared.
  const LogChannel& channel(std::uint16_t id) const;
  // Where the next record starts.
  std::uint64_t offset() const { return offset_; }

 private:
  [[noreturn]] void fail(std::uint64_t at, const std::string& problem) const;
  bool read_record(std::uint8_t& kind, std::vector<std::uint8_t>& body);
  std::uint64_t bytes_left();
  void add_channel(const std::vector<std::uint8_t>& body, std::uint64_t at);
  bool is_declared(std::uint16_t id) const;

  std::string path_;
  std::ifstream in_;
  std::uint64_t offset_ = 0;
  std::vector<LogChannel> channels_;
};

struct SampleLog {
  std::vector<LogChannel> channels;
  std::vector<LogSample> samples;
  std::string damage;  // recover_sample_log(): the FileError message of the first bad record
};

// Every sample of a complete file; throws FileError on any damage.
SampleLog read_sample_log(const std::string& path);
// Every complete record before the first damaged one (a recorder killed mid-write leaves a
// truncated tail); `damage` says what stopped the reading, empty for a complete file. Still
// throws FileError when the file cannot be opened or its header is not a sample log's.
SampleLog recover_sample_log(const std::string& path);

// Per channel: how many samples, their payload bytes and the span of their receive times.
struct ChannelSummary {
  LogChannel channel;
  std::uint64_t samples = 0;
  std::uint64_t payload_bytes = 0;
  std::int64_t first_receive_ns = 0;
  std::int64_t last_receive_ns = 0;
};
std::vector<ChannelSummary> summarize(const SampleLog& log);

}  // namespace uavslam::io
