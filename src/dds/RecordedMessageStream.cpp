#include "dds/RecordedMessageStream.hpp"

#include <utility>

#include "dds/McapChannels.hpp"
#include "io/FileError.hpp"

namespace uavslam::dds {

RecordedMessageStream::RecordedMessageStream(const std::string& path, std::set<std::string> topics)
    : path_(path), topics_(std::move(topics)), reader_(path) {
  io::mcap::Message message;
  if (reader_.next(message)) {
    first_log_time_ = message.log_time;
    first_ = std::move(message);
    return;
  }
  if (!reader_.report().complete) throw io::file_error(path, reader_.report().problem);
}

std::optional<RecordedMessage> RecordedMessageStream::next() {
  io::mcap::Message message;
  while (read_raw(message)) {
    const auto channel = reader_.channels().find(message.channel_id);
    if (channel == reader_.channels().end()) continue;  // the reader refuses such messages
    if (!topics_.empty() && topics_.count(channel->second.topic) == 0) continue;
    if (std::optional<RecordedMessage> decoded = decode(message)) return decoded;
  }
  return std::nullopt;
}

bool RecordedMessageStream::read_raw(io::mcap::Message& message) {
  if (first_) {
    message = std::move(*first_);
    first_.reset();
    return true;
  }
  return reader_.next(message);
}

std::optional<RecordedMessage> RecordedMessageStream::decode(const io::mcap::Message& message) {
  const io::mcap::Channel& channel = reader_.channels().at(message.channel_id);
  const auto schema = reader_.schemas().find(channel.schema_id);
  const std::string schema_name = schema == reader_.schemas().end() ? "" : schema->second.name;
  if (channel.message_encoding != io::kRecordingMessageEncoding || !is_recorded_type(schema_name)) {
    ++skipped_;
    if (reported_channels_.insert(channel.id).second) {
      problems_.push_back(path_ + ": channel " + channel.topic + " (schema '" + schema_name +
                          "', encoding '" + channel.message_encoding +
                          "') is not a CDR wire type of ours: its messages are skipped");
    }
    return std::nullopt;
  }
  try {
    return RecordedMessage{channel.topic, message.log_time, message.publish_time,
                           *decode_recorded(schema_name, message.data)};
  } catch (const MalformedMessage& e) {
    ++malformed_;
    problems_.push_back(path_ + ": " + channel.topic + " message " +
                        std::to_string(message.sequence) + " at log time " +
                        std::to_string(message.log_time) + " ns: " + e.what());
    return std::nullopt;
  }
}

std::set<std::string> RecordedMessageStream::topics_seen() const {
  std::set<std::string> topics;
  for (const auto& [id, channel] : reader_.channels()) topics.insert(channel.topic);
  return topics;
}

std::vector<std::string> RecordedMessageStream::take_new_problems() {
  return std::exchange(problems_, {});
}

std::string RecordedMessageStream::damage() const {
  const io::McapReadReport& r = report();
  if (r.complete || r.problem.empty()) return "";
  return path_ + ": the log stops at byte " + std::to_string(r.stopped_at) + ": " + r.problem;
}

}  // namespace uavslam::dds
