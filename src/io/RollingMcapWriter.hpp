// A recording of DDS samples as a series of MCAP files: what the `recorder` process writes on
// board and `uavslam simulate --log` writes on the desk, so that replay and offline mapping read
// both the same way. Bytes in, files out: this file knows nothing of DDS.
//
// The conventions of a recording (one place, so that every writer and reader agrees):
//   - One Schema per DDS type: name = the type's name as its PubSubType's getName() reports it
//     ("uavslam::msg::LaserScan"), encoding "omgidl", data = dds::idl_schema(name), the
//     self-contained IDL text.
//   - One Channel per topic: topic = the DDS topic name as published ("scan", "uav1/scan"),
//     message_encoding "cdr", metadata {"dds_type": the type's name}.
//   - A Message's data is the sample's CDR bytes exactly as the PubSubType's serialize() writes
//     them, encapsulation header included, so its deserialize() reads them back.
//   - log_time = when the sample was received (system clock, ns since the Unix epoch);
//     publish_time = the DDS source timestamp (same clock); sequence = how many samples of the
//     channel were handed to the recording before this one, across files and counting those a
//     write error lost: a gap in the sequence is a loss.
//   - Files: `--out flight.mcap` gives flight_000.mcap, flight_001.mcap, ... (rolled_file_path);
//     a new one when the current one would pass max_file_bytes or has been open max_file_duration.
//     Every file is self-contained (its own Header, Schemas, Channels, summary and Footer) and
//     existing files of those names are overwritten.
//
// Durability: messages reach the disk in chunks, one per flush: tick() flushes every
// flush_interval (and a chunk is flushed once it reaches chunk_size), so a process killed or a
// power cut loses at most about that much; McapStreamReader reads every flushed chunk of a file
// that was never closed.
//
// Write errors (disk full, a removed drive) never throw: the messages that did not reach the
// disk are counted as lost, the error is reported once, and every retry_interval the next
// numbered file is tried (the same number again while no try got a message to the disk), so
// recording resumes when space returns; "recording resumed" is reported once a flush succeeds.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/McapWriter.hpp"

namespace uavslam::io {

inline constexpr char kRecordingSchemaEncoding[] = "omgidl";
inline constexpr char kRecordingMessageEncoding[] = "cdr";
inline constexpr char kRecordingTypeKey[] = "dds_type";  // Channel metadata: the DDS type

// The index-th file of the recording `base`: "out/flight.mcap", 2 -> "out/flight_002.mcap"
// (".mcap" added when base has no extension).
std::string rolled_file_path(const std::string& base, std::size_t index);

// The files of the recording `base` that exist, in order, from index 0 up to the first missing.
std::vector<std::string> rolled_files(const std::string& base);

struct RollingMcapOptions {
  using Clock = std::chrono::steady_clock;
  std::uint64_t max_file_bytes = 512ull << 20;  // 0: no limit
  Clock::duration max_file_duration{0};         // 0: no limit
  Clock::duration flush_interval = std::chrono::seconds(1);
  Clock::duration retry_interval = std::chrono::seconds(5);
  std::size_t chunk_size = 1 << 20;  // bytes of messages flushed as one chunk at most
  bool sync_on_flush = true;         // fdatasync on every flush: a power cut loses no chunk
  McapCompression compression = McapCompression::kNone;   // of every chunk of every file
  std::function<Clock::time_point()> clock = Clock::now;  // tests set their own
  // Says what people should know (a new file, a write error, recording resumed); one line each.
  std::function<void(const std::string&)> report = [](const std::string&) {};
};

struct RecordedTopic {
  std::string topic;
  std::string type;
  std::uint64_t handed = 0;   // messages handed to write()
  std::uint64_t written = 0;  // of those, flushed to a file
  std::uint64_t lost = 0;     // of those, lost to a write error
};

class RollingMcapWriter {
 public:
  // Opens the first file, rolled_file_path(base, 0). FileError when it cannot: a recording that
  // cannot start is a configuration error, one that stops later is not.
  RollingMcapWriter(std::string base, RollingMcapOptions options);
  // Closes like close(), reporting a failure through options.report.
  ~RollingMcapWriter();
  RollingMcapWriter(const RollingMcapWriter&) = delete;
  RollingMcapWriter& operator=(const RollingMcapWriter&) = delete;

  // Declares a topic of the DDS type `type` whose IDL is `idl`, and returns its handle (from 0)
  // for write(); the same topic again returns the same handle (std::invalid_argument for a
  // different type).
  std::size_t add_topic(const std::string& topic, const std::string& type, const std::string& idl);

  // Appends one message of topic handle `topic`; rolls over to the next file first when due.
  // Never throws a FileError: a message that cannot be written is counted as lost.
  void write(std::size_t topic, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
             const std::uint8_t* data, std::size_t size);
  // Flushes when flush_interval has passed since the last flush: call it regularly.
  void tick();
  // Hands every message written so far to the disk now.
  void flush();
  // Flushes and closes the current file properly (summary, Footer); a second call does nothing.
  void close();

  const std::vector<RecordedTopic>& topics() const { return topics_; }
  std::uint64_t lost() const;
  // Every file opened so far, in order, that holds messages or is being written (also those a
  // write error cut short).
  const std::vector<std::string>& files() const { return files_; }
  // The file being written; empty while a write error waits for its retry, or after close().
  std::string current_file() const;

 private:
  struct TopicState {
    std::string idl;
    std::uint16_t channel = 0;  // in the current file
    std::uint64_t pending = 0;  // written to the current chunk, not yet flushed
  };

  bool open_next();
  void register_topic(std::size_t topic);
  bool ready_for(std::size_t size);
  bool roll_due(std::size_t size) const;
  bool close_file(bool will_retry);
  void fail(const std::string& error, bool will_retry);
  void settle_pending(bool written);

  std::string base_;
  RollingMcapOptions options_;
  std::unique_ptr<McapWriter> file_;
  std::size_t next_index_ = 0;
  RollingMcapOptions::Clock::time_point opened_at_{};
  RollingMcapOptions::Clock::time_point flushed_at_{};
  RollingMcapOptions::Clock::time_point retry_at_{};
  std::uint64_t messages_in_file_ = 0;
  bool file_has_data_ = false;       // a flush of the current file has succeeded
  std::uint64_t flushed_bytes_ = 0;  // the current file's size at its last flush
  std::uint64_t lost_since_failure_ = 0;
  bool failing_ = false;  // a write error was reported, no file has opened since
  bool closed_ = false;
  std::vector<RecordedTopic> topics_;
  std::vector<TopicState> states_;
  std::vector<std::string> files_;
};

}  // namespace uavslam::io
