// mcap_compression_table RECORDING.mcap WORK_DIR: rewrites a recording's messages the way the
// recorder writes them (RollingMcapWriter, one chunk per second of log time, no roll-over) once
// per chunk compression, and prints a Markdown table of file size, write time and read time
// (McapStreamReader and McapIndexedReader over every message), each the best of three runs. The
// files are written without fdatasync: the table measures the CPU cost of compression, not the
// disk. Not a test; docs/recordings.md shows its output for the demo flight.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "io/McapCompression.hpp"
#include "io/McapReader.hpp"
#include "io/RollingMcapWriter.hpp"

namespace uavslam {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Recording {
  std::vector<io::mcap::Message> messages;
  std::map<std::uint16_t, io::mcap::Channel> channels;
  std::map<std::uint16_t, io::mcap::Schema> schemas;
};

Recording load(const std::string& path) {
  io::McapStreamReader reader(path);
  Recording recording;
  io::mcap::Message message;
  while (reader.next(message)) recording.messages.push_back(message);
  if (!reader.report().complete) {
    std::cerr << path << ": read up to byte " << reader.report().stopped_at << ": "
              << reader.report().problem << "\n";
  }
  recording.channels = reader.channels();
  recording.schemas = reader.schemas();
  return recording;
}

// Seconds `run` takes, the best of three.
double best_seconds(const std::function<void()>& run) {
  double best = 1e300;
  for (int i = 0; i < 3; ++i) {
    const auto start = Clock::now();
    run();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  return best;
}

// Writes the recording as the recorder does; log time drives its flush clock, so each chunk holds
// one second of flight as on board. Returns the file written.
std::string write(const Recording& recording, const std::string& base,
                  io::McapCompression compression) {
  Clock::time_point now{};
  io::RollingMcapOptions options;
  options.compression = compression;
  options.sync_on_flush = false;
  options.max_file_bytes = 0;
  options.clock = [&now] { return now; };
  io::RollingMcapWriter writer(base, options);
  std::map<std::uint16_t, std::size_t> topic_of;
  for (const auto& [id, channel] : recording.channels) {
    const auto schema = recording.schemas.find(channel.schema_id);
    const bool known = schema != recording.schemas.end();
    topic_of[id] = writer.add_topic(channel.topic, known ? schema->second.name : "",
                                    known ? schema->second.data : "");
  }
  for (const io::mcap::Message& m : recording.messages) {
    now = Clock::time_point(std::chrono::nanoseconds(m.log_time));
    writer.write(topic_of.at(m.channel_id), m.log_time, m.publish_time, m.data.data(),
                 m.data.size());
    writer.tick();
  }
  writer.close();
  return writer.files().front();
}

std::size_t stream_read(const std::string& file) {
  io::McapStreamReader reader(file);
  io::mcap::Message message;
  std::size_t count = 0;
  while (reader.next(message)) ++count;
  return count;
}

std::size_t indexed_read(const std::string& file) {
  io::McapIndexedReader reader(file);
  std::size_t count = 0;
  reader.read_messages(0, [&](const io::mcap::Message&) {
    ++count;
    return true;
  });
  return count;
}

int run(const std::string& input, const fs::path& work_dir) {
  const Recording recording = load(input);
  std::uint64_t payload = 0;
  for (const io::mcap::Message& m : recording.messages) payload += m.data.size();
  std::printf("%s: %zu messages, %.1f MB of message data\n\n", input.c_str(),
              recording.messages.size(), static_cast<double>(payload) / 1e6);
  std::printf("| compression | file size | of none | write | stream read | indexed read |\n");
  std::printf("|---|---:|---:|---:|---:|---:|\n");
  double none_size = 0;
  for (const std::string& name : io::mcap_compression_names()) {
    const std::string base = (work_dir / ("flight_" + name + ".mcap")).string();
    std::string file;
    const double write_s =
        best_seconds([&] { file = write(recording, base, *io::parse_mcap_compression(name)); });
    std::size_t streamed = 0, indexed = 0;
    const double stream_s = best_seconds([&] { streamed = stream_read(file); });
    const double indexed_s = best_seconds([&] { indexed = indexed_read(file); });
    if (streamed != recording.messages.size() || indexed != recording.messages.size()) {
      std::cerr << file << ": read back " << streamed << " and " << indexed << " messages of "
                << recording.messages.size() << "\n";
      return 1;
    }
    const auto size = static_cast<double>(fs::file_size(file));
    if (name == "none") none_size = size;
    std::printf("| %s | %.1f MB | %.0f %% | %.2f s | %.2f s | %.2f s |\n", name.c_str(), size / 1e6,
                100 * size / none_size, write_s, stream_s, indexed_s);
  }
  return 0;
}

}  // namespace
}  // namespace uavslam

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: mcap_compression_table RECORDING.mcap WORK_DIR (where the three "
                 "rewritten files are left)\n";
    return 2;
  }
  try {
    std::filesystem::create_directories(argv[2]);
    return uavslam::run(argv[1], argv[2]);
  } catch (const std::exception& e) {
    std::cerr << "mcap_compression_table: " << e.what() << "\n";
    return 1;
  }
}
