// What an MCAP file holds, for people: per channel its topic, type, message count, bytes and
// time span, and whether the file was read to its end (`recorder --dump`, tests of recordings).
// Streams the whole file, so it lists what a killed recorder left as well as a closed file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/McapReader.hpp"

namespace uavslam::io {

struct McapChannelListing {
  std::uint16_t id = 0;
  std::string topic;
  std::string type;  // the Channel's "dds_type" metadata, else its Schema's name
  std::string message_encoding;
  std::uint64_t messages = 0;
  std::uint64_t bytes = 0;           // of message data
  std::uint64_t first_log_time = 0;  // ns; 0 without messages
  std::uint64_t last_log_time = 0;
};

struct McapListing {
  std::string path;
  std::vector<McapChannelListing> channels;  // by channel id
  std::uint64_t messages = 0;
  McapReadReport report;  // complete, or where and why reading stopped
};

// Reads every message of the file. FileError only when it cannot be opened.
McapListing list_mcap(const std::string& path);

// The messages on the channels of `topic` (0 when there is none).
std::uint64_t messages_on(const McapListing& listing, const std::string& topic);

// The listing as text, one line per channel, the last line the report:
//   flight_000.mcap: 600 messages on 2 channels
//     rec/scan  uavslam::msg::LaserScan  100 messages  443200 bytes  2024-05-01T10:00:00.125Z
//       .. 2024-05-01T10:00:02.600Z (2.475 s)
//   complete | damaged: stopped at byte 1234: truncated inside a Chunk record ...
std::string format_listing(const McapListing& listing);

}  // namespace uavslam::io
