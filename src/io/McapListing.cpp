#include "io/McapListing.hpp"

#include <cstdio>
#include <ctime>
#include <map>

#include "io/RollingMcapWriter.hpp"

namespace uavslam::io {

namespace {

McapChannelListing describe(const mcap::Channel& channel,
                            const std::map<std::uint16_t, mcap::Schema>& schemas) {
  McapChannelListing listed;
  listed.id = channel.id;
  listed.topic = channel.topic;
  listed.message_encoding = channel.message_encoding;
  const auto type = channel.metadata.find(kRecordingTypeKey);
  const auto schema = schemas.find(channel.schema_id);
  if (type != channel.metadata.end()) {
    listed.type = type->second;
  } else if (schema != schemas.end()) {
    listed.type = schema->second.name;
  }
  return listed;
}

McapChannelListing& entry(McapListing& listing,
                          const std::map<std::uint16_t, mcap::Channel>& channels,
                          const std::map<std::uint16_t, mcap::Schema>& schemas,
                          std::uint16_t channel_id) {
  for (McapChannelListing& c : listing.channels) {
    if (c.id == channel_id) return c;
  }
  // The reader has met the Channel record before any message on it (else it stops before
  // handing the message out).
  const auto channel = channels.find(channel_id);
  if (channel != channels.end()) {
    listing.channels.push_back(describe(channel->second, schemas));
  } else {
    listing.channels.push_back({});
    listing.channels.back().id = channel_id;
  }
  return listing.channels.back();
}

// Channels without messages are listed too (a topic that stayed silent is worth seeing); only
// the summary of a closed file knows them.
void add_silent_channels(McapListing& listing) {
  McapIndexedReader indexed(listing.path);
  if (!indexed.has_summary()) return;
  for (const auto& [id, channel] : indexed.channels()) {
    entry(listing, indexed.channels(), indexed.schemas(), id);
  }
}

// "2024-05-01T10:00:00.125Z" (UTC, milliseconds).
std::string utc_text(std::uint64_t ns) {
  const auto seconds = static_cast<std::time_t>(ns / 1000000000u);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char date[32], text[48];
  std::strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%S", &utc);
  std::snprintf(text, sizeof(text), "%s.%03uZ", date,
                static_cast<unsigned>(ns % 1000000000u / 1000000u));
  return text;
}

}  // namespace

McapListing list_mcap(const std::string& path) {
  McapListing listing;
  listing.path = path;
  McapStreamReader reader(path);
  mcap::Message message;
  while (reader.next(message)) {
    McapChannelListing& c = entry(listing, reader.channels(), reader.schemas(), message.channel_id);
    if (c.messages == 0 || message.log_time < c.first_log_time) c.first_log_time = message.log_time;
    if (message.log_time > c.last_log_time) c.last_log_time = message.log_time;
    ++c.messages;
    c.bytes += message.data.size();
    ++listing.messages;
  }
  listing.report = reader.report();
  if (listing.report.complete) add_silent_channels(listing);
  std::map<std::uint16_t, McapChannelListing> by_id;
  for (McapChannelListing& c : listing.channels) by_id[c.id] = std::move(c);
  listing.channels.clear();
  for (auto& [id, c] : by_id) listing.channels.push_back(std::move(c));
  return listing;
}

std::uint64_t messages_on(const McapListing& listing, const std::string& topic) {
  std::uint64_t messages = 0;
  for (const McapChannelListing& c : listing.channels) {
    if (c.topic == topic) messages += c.messages;
  }
  return messages;
}

std::string format_listing(const McapListing& listing) {
  std::string text = listing.path + ": " + std::to_string(listing.messages) + " messages on " +
                     std::to_string(listing.channels.size()) + " channels\n";
  for (const McapChannelListing& c : listing.channels) {
    char line[512];
    std::snprintf(line, sizeof(line), "  %-20s %-28s %8llu messages %12llu bytes", c.topic.c_str(),
                  c.type.c_str(), static_cast<unsigned long long>(c.messages),
                  static_cast<unsigned long long>(c.bytes));
    text += line;
    if (c.messages > 0) {
      std::snprintf(line, sizeof(line), "  %s .. %s (%.3f s)", utc_text(c.first_log_time).c_str(),
                    utc_text(c.last_log_time).c_str(),
                    static_cast<double>(c.last_log_time - c.first_log_time) * 1e-9);
      text += line;
    }
    text += "\n";
  }
  for (const std::string& skipped : listing.report.skipped) text += "skipped: " + skipped + "\n";
  if (listing.report.complete) return text + "complete\n";
  return text + "damaged: stopped at byte " + std::to_string(listing.report.stopped_at) + ": " +
         listing.report.problem + "\n";
}

}  // namespace uavslam::io
