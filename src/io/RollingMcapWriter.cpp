#include "io/RollingMcapWriter.hpp"

#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace uavslam::io {

namespace fs = std::filesystem;

namespace {

// What a message adds to a file besides its data: the record prefix, its fields and its entry
// in the chunk's Message Index.
constexpr std::uint64_t kMessageOverhead = mcap::kRecordPrefixSize + mcap::kMessageFieldsSize + 16;

std::string seconds_text(RollingMcapOptions::Clock::duration d) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g s", std::chrono::duration<double>(d).count());
  return text;
}

}  // namespace

std::string rolled_file_path(const std::string& base, std::size_t index) {
  const fs::path path(base);
  std::string extension = path.extension().string();
  if (extension.empty()) extension = ".mcap";
  char number[24];
  std::snprintf(number, sizeof(number), "_%03zu", index);
  return (path.parent_path() / (path.stem().string() + number + extension)).string();
}

std::vector<std::string> rolled_files(const std::string& base) {
  std::vector<std::string> files;
  std::error_code ignored;
  while (fs::exists(rolled_file_path(base, files.size()), ignored)) {
    files.push_back(rolled_file_path(base, files.size()));
  }
  return files;
}

RollingMcapWriter::RollingMcapWriter(std::string base, RollingMcapOptions options)
    : base_(std::move(base)), options_(std::move(options)) {
  const fs::path parent = fs::path(base_).parent_path();
  std::error_code ignored;  // a failure shows as the FileError naming the file
  if (!parent.empty()) fs::create_directories(parent, ignored);
  McapWriterOptions first;
  first.chunk_size = std::numeric_limits<std::size_t>::max();  // chunks end at our flushes
  first.sync_on_flush = options_.sync_on_flush;
  first.compression = options_.compression;
  file_ = std::make_unique<McapWriter>(rolled_file_path(base_, 0), first);
  next_index_ = 1;
  files_.push_back(file_->path());
  opened_at_ = flushed_at_ = options_.clock();
  flushed_bytes_ = file_->bytes_written();
}

RollingMcapWriter::~RollingMcapWriter() {
  try {
    close();
  } catch (...) {  // close() reports write errors itself; nothing else to say here
  }
}

std::size_t RollingMcapWriter::add_topic(const std::string& topic, const std::string& type,
                                         const std::string& idl) {
  for (std::size_t i = 0; i < topics_.size(); ++i) {
    if (topics_[i].topic != topic) continue;
    if (topics_[i].type != type || states_[i].idl != idl) {
      throw std::invalid_argument("topic '" + topic + "' declared as " + topics_[i].type +
                                  " and as " + type);
    }
    return i;
  }
  RecordedTopic& added = topics_.emplace_back();
  added.topic = topic;
  added.type = type;
  states_.push_back({idl, 0, 0});
  if (file_) register_topic(topics_.size() - 1);
  return topics_.size() - 1;
}

void RollingMcapWriter::write(std::size_t topic, std::uint64_t log_time_ns,
                              std::uint64_t publish_time_ns, const std::uint8_t* data,
                              std::size_t size) {
  RecordedTopic& recorded = topics_.at(topic);
  // The MCAP sequence is a u32; it wraps after 4e9 messages of one channel (200 days of IMU).
  const auto sequence = static_cast<std::uint32_t>(recorded.handed++);
  if (!ready_for(size)) {
    ++recorded.lost;
    ++lost_since_failure_;
    return;
  }
  try {
    file_->write(states_[topic].channel, sequence, log_time_ns, publish_time_ns, data, size);
  } catch (const FileError& e) {
    ++recorded.lost;
    ++lost_since_failure_;
    fail(e.what(), true);
    return;
  }
  ++states_[topic].pending;
  ++messages_in_file_;
  if (file_->bytes_written() - flushed_bytes_ >= options_.chunk_size) flush();
}

void RollingMcapWriter::tick() {
  if (file_ && options_.clock() - flushed_at_ >= options_.flush_interval) flush();
}

void RollingMcapWriter::flush() {
  flushed_at_ = options_.clock();
  if (!file_ || file_->bytes_written() == flushed_bytes_) return;
  try {
    file_->flush();
  } catch (const FileError& e) {
    fail(e.what(), true);
    return;
  }
  flushed_bytes_ = file_->bytes_written();
  settle_pending(true);
  file_has_data_ = true;
  if (failing_) {
    failing_ = false;
    options_.report("recording resumed in " + file_->path() + " (" +
                    std::to_string(lost_since_failure_) + " messages lost)");
  }
}

void RollingMcapWriter::close() {
  if (closed_) return;
  closed_ = true;
  if (file_) close_file(false);
}

std::uint64_t RollingMcapWriter::lost() const {
  std::uint64_t lost = 0;
  for (const RecordedTopic& t : topics_) lost += t.lost;
  return lost;
}

std::string RollingMcapWriter::current_file() const {
  return file_ ? file_->path() : "";
}

bool RollingMcapWriter::open_next() {
  const std::string path = rolled_file_path(base_, next_index_);
  McapWriterOptions options;
  options.chunk_size = std::numeric_limits<std::size_t>::max();
  options.sync_on_flush = options_.sync_on_flush;
  options.compression = options_.compression;
  try {
    file_ = std::make_unique<McapWriter>(path, options);
  } catch (const FileError& e) {
    // The same number is tried again: the numbers of a recording have no gaps.
    fail(e.what(), true);
    return false;
  }
  ++next_index_;
  files_.push_back(path);
  opened_at_ = flushed_at_ = options_.clock();
  flushed_bytes_ = file_->bytes_written();
  messages_in_file_ = 0;
  file_has_data_ = false;
  for (std::size_t i = 0; i < topics_.size(); ++i) register_topic(i);
  return true;
}

void RollingMcapWriter::register_topic(std::size_t topic) {
  const RecordedTopic& t = topics_[topic];
  const std::uint16_t schema =
      file_->add_schema(t.type, kRecordingSchemaEncoding, states_[topic].idl);
  states_[topic].channel =
      file_->add_channel(schema, t.topic, kRecordingMessageEncoding, {{kRecordingTypeKey, t.type}});
}

// Whether a message of `size` bytes can be written now: opens the next file when a retry or a
// roll-over is due.
bool RollingMcapWriter::ready_for(std::size_t size) {
  if (closed_) throw std::logic_error(base_ + ": write after close()");
  if (!file_) return options_.clock() >= retry_at_ && open_next();
  if (!roll_due(size)) return true;
  const std::string previous = file_->path();
  const std::uint64_t messages = messages_in_file_;
  if (!close_file(true)) return false;
  if (!open_next()) return false;
  options_.report(previous + ": closed after " + std::to_string(messages) +
                  " messages; recording to " + file_->path());
  return true;
}

bool RollingMcapWriter::roll_due(std::size_t size) const {
  if (messages_in_file_ == 0) return false;  // every file holds a message, however large
  if (options_.max_file_bytes > 0 &&
      file_->bytes_written() + size + kMessageOverhead > options_.max_file_bytes) {
    return true;
  }
  return options_.max_file_duration.count() > 0 &&
         options_.clock() - opened_at_ >= options_.max_file_duration;
}

// Flushes first, so that a failing close() (the summary) still leaves every message counted
// where it is: on disk, in a file McapStreamReader reads.
bool RollingMcapWriter::close_file(bool will_retry) {
  flush();
  if (!file_) return false;
  try {
    file_->close();
  } catch (const FileError& e) {
    fail(e.what(), will_retry);
    return false;
  }
  file_.reset();
  return true;
}

void RollingMcapWriter::fail(const std::string& error, bool will_retry) {
  if (!failing_) {
    failing_ = true;
    lost_since_failure_ = 0;
    options_.report(error + (will_retry ? "; messages are counted as lost until a new file opens "
                                          "(tried every " +
                                              seconds_text(options_.retry_interval) + ")"
                                        : ""));
  }
  settle_pending(false);
  if (file_) {
    try {
      file_->close();  // after an error it only releases the file, which stays as it is
    } catch (const FileError&) {
    }
    file_.reset();
    // A file that never got a message to the disk is taken again by the next try, so that a
    // long outage leaves no trail of empty files.
    if (!file_has_data_) {
      --next_index_;
      files_.pop_back();
    }
  }
  retry_at_ = options_.clock() + options_.retry_interval;
}

void RollingMcapWriter::settle_pending(bool written) {
  for (std::size_t i = 0; i < states_.size(); ++i) {
    (written ? topics_[i].written : topics_[i].lost) += states_[i].pending;
    if (!written) lost_since_failure_ += states_[i].pending;
    states_[i].pending = 0;
  }
}

}  // namespace uavslam::io
