// The messages of an MCAP recording, streamed in file order and decoded as the wire types of
// their channels' schemas (RecordedMessages.hpp): what a replay publishes and the offline mapper
// reads, however large the file (one chunk in memory at a time). A file a recorder left behind
// when it was killed is read up to its damage: every whole message before it, and report() says
// where reading stopped and why.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "dds/RecordedMessages.hpp"
#include "io/McapReader.hpp"

namespace uavslam::dds {

struct RecordedMessage {
  std::string topic;
  std::uint64_t log_time = 0;      // ns
  std::uint64_t publish_time = 0;  // ns
  RecordedSample sample;
};

class RecordedMessageStream {
 public:
  // Opens `path` and reads up to its first message. `topics`: the channels wanted (empty: all).
  // io::FileError naming the path when it cannot be opened, is not an MCAP file, or is damaged
  // before its first whole message (nothing to read).
  RecordedMessageStream(const std::string& path, std::set<std::string> topics);

  // The next message on a wanted channel, decoded; nullopt at the end of the file or where it is
  // damaged. Messages whose schema is not a wire type of ours, or not CDR, are skipped and
  // counted; messages whose bytes do not decode are counted as malformed; both are described
  // (take_new_problems), a channel's unknown schema once.
  std::optional<RecordedMessage> next();

  // The log_time of the file's first message on any channel: the origin of the replay timeline,
  // the same for every process that replays the file.
  std::uint64_t first_log_time() const { return first_log_time_; }
  // The topics of every channel met so far, wanted or not.
  std::set<std::string> topics_seen() const;
  std::size_t malformed() const { return malformed_; }
  std::size_t skipped() const { return skipped_; }
  // "path: reason" of each message or channel skipped since the last call.
  std::vector<std::string> take_new_problems();
  // Where and why reading stopped; complete once the end of a whole file was read.
  const io::McapReadReport& report() const { return reader_.report(); }
  // "" when reading reached the file's end, else "path: the log stops at byte N: problem".
  std::string damage() const;
  const std::string& path() const { return path_; }

 private:
  bool read_raw(io::mcap::Message& message);
  std::optional<RecordedMessage> decode(const io::mcap::Message& message);

  std::string path_;
  std::set<std::string> topics_;
  io::McapStreamReader reader_;
  std::optional<io::mcap::Message> first_;  // read ahead by the constructor
  std::uint64_t first_log_time_ = 0;
  std::size_t malformed_ = 0;
  std::size_t skipped_ = 0;
  std::set<std::uint16_t> reported_channels_;  // whose unknown schema was described
  std::vector<std::string> problems_;
};

}  // namespace uavslam::dds
