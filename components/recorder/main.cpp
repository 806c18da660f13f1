// recorder: subscribes `scan` and `imu` (sensor QoS) and writes every sample it receives, as the
// CDR bytes its PubSubType serialises, to a recording of MCAP files (the conventions, roll-over,
// flushing and write errors: src/io/RollingMcapWriter.hpp). A writer thread owns the files: the
// DDS threads only serialise and queue, so a slow disk costs counted drops, never a stalled
// reader, and a full disk costs counted losses, never the flight. `--dump FILE` lists a file.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <deque>
#include <exception>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>

#include <msg/ImuPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/TwistPubSubTypes.h>
#include <CLI/CLI.hpp>

#include "common/HandoffQueue.hpp"
#include "common/IncompatibleQos.hpp"
#include "common/NodeOptions.hpp"
#include "common/RunNode.hpp"
#include "common/StopRequest.hpp"
#include "dds/IdlSchemas.hpp"
#include "dds/Participant.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "io/McapCompression.hpp"
#include "io/McapListing.hpp"
#include "io/RollingMcapWriter.hpp"

namespace uavslam {
namespace {

const std::vector<std::string> kRecordableTopics{dds::kScanTopic, dds::kImuTopic,
                                                 dds::kVelocityTopic};

struct RecorderOptions {
  std::string out = "out/recording.mcap";
  std::vector<std::string> topics = kRecordableTopics;
  int queue_capacity = 4000;    // samples: ~17 s of scan (40 Hz) + imu (200 Hz)
  double max_file_mb = 512;     // 0: no limit
  double max_file_seconds = 0;  // 0: no limit
  double flush_seconds = 1;
  double retry_seconds = 5;
  std::string compression = "none";  // of the chunks: one of io::mcap_compression_names()
  std::string dump;
};

// A sample on its way from a DDS thread to the writer thread.
struct QueuedSample {
  std::size_t topic = 0;  // the recording's topic handle
  std::uint64_t receive_time_ns = 0;
  std::uint64_t source_time_ns = 0;
  std::vector<std::uint8_t> payload;
};

io::RollingMcapOptions recording_options(const RecorderOptions& o) {
  const auto duration = [](double seconds) {
    return std::chrono::duration_cast<io::RollingMcapOptions::Clock::duration>(
        std::chrono::duration<double>(seconds));
  };
  io::RollingMcapOptions r;
  r.max_file_bytes = static_cast<std::uint64_t>(o.max_file_mb * 1024 * 1024);
  r.max_file_duration = duration(o.max_file_seconds);
  r.flush_interval = duration(o.flush_seconds);
  r.retry_interval = duration(o.retry_seconds);
  r.compression = io::parse_mcap_compression(o.compression).value();  // checked when read
  r.report = [](const std::string& line) { std::cerr << "recorder: " << line << "\n"; };
  return r;
}

std::uint64_t now_ns() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::system_clock::now().time_since_epoch())
                                        .count());
}

// The sample's CDR bytes exactly as PubSubType::serialize writes them (encapsulation included),
// so PubSubType::deserialize reads them back. False if serialisation fails.
template <typename PubSubType>
bool to_cdr(PubSubType& type, const typename PubSubType::type& sample,
            std::vector<std::uint8_t>& out) {
  void* data = const_cast<typename PubSubType::type*>(&sample);  // serialize() only reads it
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(data)());
  if (!type.serialize(data, &payload)) return false;
  out.assign(payload.data, payload.data + payload.length);
  return true;
}

// Per topic, counted by the DDS thread (the writer counts what reaches the files).
struct TopicCounts {
  std::atomic<std::uint64_t> received{0};
  std::atomic<std::uint64_t> dropped{0};  // queue full, or not serialisable
};

class RecorderNode {
 public:
  RecorderNode(const process::NodeOptions& node, const RecorderOptions& o)
      : participant_(node.domain, process::profiles_path(node), node.participant_profile,
                     "recorder"),
        recording_(o.out, recording_options(o)),
        queue_(static_cast<std::size_t>(o.queue_capacity)) {
    for (const std::string& base : o.topics) {
      const std::string topic = dds::topic_name(node.vehicle, base);
      if (base == dds::kScanTopic) {
        scans_ = subscribe<msg::LaserScanPubSubType>(topic,
                                                     node.profile(base, "sensor_recorder_reader"));
      }
      if (base == dds::kImuTopic) {
        imu_ = subscribe<msg::ImuPubSubType>(topic, node.profile(base, "sensor_recorder_reader"));
      }
      if (base == dds::kVelocityTopic) {
        velocity_ = subscribe<msg::TwistWithCovarianceStampedPubSubType>(
            topic, node.profile(base, "sensor_recorder_reader"));
      }
    }
  }
  ~RecorderNode() { finish(); }

  int run() {
    std::cerr << "recorder: recording " << topic_list() << " to " << recording_.current_file()
              << " (domain " << participant_.domain_id() << ")\n";
    writer_ = std::thread([this] { write_loop(); });  // from now on it alone uses recording_
    std::size_t scan_writers = 0, imu_writers = 0, velocity_writers = 0;
    while (!process::stop_requested() && !writer_failed_) {
      if (scans_) watch(*scans_, scan_writers);
      if (imu_) watch(*imu_, imu_writers);
      if (velocity_) watch(*velocity_, velocity_writers);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    finish();
    if (writer_error_) std::rethrow_exception(writer_error_);
    print_counts();
    if (recording_.lost() == 0) return 0;
    std::cerr << "recorder: " << recording_.lost() << " samples lost to write errors\n";
    return 1;
  }

 private:
  // Stops on a publisher whose QoS cannot match; says when publishers come and go (a recording
  // with a silent topic is then explained by its stderr).
  template <typename Reader>
  static void watch(const Reader& reader, std::size_t& writers_seen) {
    process::throw_if_incompatible(reader);
    const std::size_t writers = reader.matched();
    if (writers == writers_seen) return;
    writers_seen = writers;
    std::cerr << "recorder: " << reader.topic() << ": " << writers << " writer(s) matched\n";
  }

  template <typename PubSubType>
  std::unique_ptr<dds::Reader<PubSubType>> subscribe(const std::string& topic,
                                                     const std::string& profile) {
    auto type = std::make_shared<PubSubType>();
    const std::optional<std::string> idl = dds::idl_schema(type->getName());
    if (!idl) throw std::logic_error(std::string("no IDL for ") + type->getName());
    const std::size_t handle = recording_.add_topic(topic, type->getName(), *idl);
    // counts_ is indexed by topic handle: one new handle per subscribed topic, in order.
    if (handle != counts_.size()) throw std::logic_error("topic '" + topic + "' subscribed twice");
    TopicCounts& counts = counts_.emplace_back();
    // Runs on the reader's DDS thread: serialise, queue, count; never touch the file.
    auto on_sample = [this, type, handle, &counts](const typename PubSubType::type& sample,
                                                   const eprosima::fastdds::dds::SampleInfo& info) {
      ++counts.received;
      const auto source_ns =
          static_cast<std::uint64_t>(std::max<std::int64_t>(0, info.source_timestamp.to_ns()));
      QueuedSample received{handle, now_ns(), source_ns, {}};
      if (!to_cdr(*type, sample, received.payload) || !queue_.push(std::move(received))) {
        ++counts.dropped;
      }
    };
    return std::make_unique<dds::Reader<PubSubType>>(participant_, topic, profile, on_sample);
  }

  // The writer thread: writes what waits and flushes every --flush-seconds. A write error is
  // the recording's to count and report; only a bug ends this loop early.
  void write_loop() {
    std::vector<QueuedSample> batch;
    try {
      while (queue_.take_all(batch, std::chrono::milliseconds(100))) {
        for (const QueuedSample& s : batch) {
          recording_.write(s.topic, s.receive_time_ns, s.source_time_ns, s.payload.data(),
                           s.payload.size());
        }
        recording_.tick();
      }
    } catch (const std::exception& e) {
      writer_error_ = std::make_exception_ptr(std::runtime_error(e.what()));
      writer_failed_ = true;
      queue_.close();  // from now on every sample counts as dropped
    }
  }

  // Stops the readers first (no more samples), then lets the writer drain the queue and closes
  // the file (summary, Footer). Safe to call twice, and from the destructor when run() throws.
  void finish() {
    scans_.reset();
    imu_.reset();
    velocity_.reset();
    queue_.close();
    if (writer_.joinable()) writer_.join();
    recording_.close();
  }

  std::string topic_list() const {
    std::string out;
    for (const io::RecordedTopic& t : recording_.topics())
      out += (out.empty() ? "" : ", ") + t.topic;
    return out;
  }

  // After finish(): the writer thread has ended.
  void print_counts() const {
    for (std::size_t i = 0; i < counts_.size(); ++i) {
      const io::RecordedTopic& t = recording_.topics()[i];
      std::cerr << "recorder: " << t.topic << ": " << counts_[i].received << " received, "
                << t.written << " written, " << counts_[i].dropped << " dropped, " << t.lost
                << " lost to write errors\n";
    }
    std::string files;
    for (const std::string& f : recording_.files()) files += (files.empty() ? "" : ", ") + f;
    std::cerr << "recorder: " << recording_.files().size() << " file(s): " << files << "\n";
  }

  dds::Participant participant_;
  io::RollingMcapWriter recording_;
  process::HandoffQueue<QueuedSample> queue_;
  std::deque<TopicCounts> counts_;  // by topic handle; a deque never moves its elements
  std::unique_ptr<dds::Reader<msg::LaserScanPubSubType>> scans_;
  std::unique_ptr<dds::Reader<msg::ImuPubSubType>> imu_;
  std::unique_ptr<dds::Reader<msg::TwistWithCovarianceStampedPubSubType>> velocity_;
  std::thread writer_;
  std::atomic<bool> writer_failed_{false};
  std::exception_ptr writer_error_;
};

// --dump: one line per channel, then whether the file was read to its end (exit 1 if not).
int dump(const std::string& path) {
  const io::McapListing listing = io::list_mcap(path);
  std::cout << io::format_listing(listing) << std::flush;
  return listing.report.complete ? 0 : 1;
}

std::vector<std::string> without_duplicates(const std::vector<std::string>& topics) {
  std::vector<std::string> out;
  for (const std::string& t : topics) {
    if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
  }
  return out;
}

void apply_own_config(const CLI::App& app, const io::YamlReader& section, RecorderOptions& o) {
  section.expect_keys_only({"out", "topics", "queue_capacity", "max_file_mb", "max_file_seconds",
                            "flush_seconds", "retry_seconds", "compression"});
  if (process::unset(app, "--out")) o.out = section.get_string_or("out", o.out);
  if (process::unset(app, "--topics") && section.has("topics")) {
    o.topics.clear();
    for (const io::YamlReader& t : section.at("topics").elements()) {
      o.topics.push_back(t.as_choice(kRecordableTopics));
    }
  }
  if (process::unset(app, "--compression") && section.has("compression")) {
    o.compression = section.at("compression").as_choice(io::mcap_compression_names());
  }
  if (process::unset(app, "--queue-capacity")) {
    o.queue_capacity =
        section.get_int_or("queue_capacity", o.queue_capacity, io::NumberRange::at_least(1));
  }
  const auto seconds = [&](const char* flag, const char* key, double& value,
                           io::NumberRange range) {
    if (process::unset(app, flag)) value = section.get_double_or(key, value, range);
  };
  seconds("--max-file-mb", "max_file_mb", o.max_file_mb, io::NumberRange::non_negative());
  seconds("--max-file-seconds", "max_file_seconds", o.max_file_seconds,
          io::NumberRange::non_negative());
  seconds("--flush-seconds", "flush_seconds", o.flush_seconds, io::NumberRange::positive());
  seconds("--retry-seconds", "retry_seconds", o.retry_seconds, io::NumberRange::positive());
}

}  // namespace
}  // namespace uavslam

int main(int argc, char** argv) {
  CLI::App app{
      "recorder: subscribes scan and imu and writes every sample (CDR bytes) to MCAP files: "
      "--out out/flight.mcap writes out/flight_000.mcap, then flight_001.mcap, ... at each "
      "roll-over (existing files of those names are overwritten); each file is complete on its "
      "own. A write error (disk full) is reported once, its samples are counted as lost, a new "
      "file is tried every --retry-seconds, and the exit code is 1. --dump FILE lists a file"};
  uavslam::process::NodeOptions node;
  uavslam::RecorderOptions options;
  uavslam::process::add_node_options(app, node);
  app.add_option(
         "--out", options.out,
         "the recording's name: NAME.mcap gives the files NAME_000.mcap, NAME_001.mcap, ...")
      ->capture_default_str();
  app.add_option("--topics", options.topics, "topics to record, comma-separated")
      ->delimiter(',')
      ->check(CLI::IsMember(uavslam::kRecordableTopics))
      ->capture_default_str();
  app.add_option("--queue-capacity", options.queue_capacity,
                 "samples waiting for the disk before new ones are dropped")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--max-file-mb", options.max_file_mb,
                 "start the next file before one passes this size (MiB; 0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--max-file-seconds", options.max_file_seconds,
                 "start the next file after one has been open this long (0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--flush-seconds", options.flush_seconds,
                 "hand the samples to the disk (fdatasync) this often: what a crash can lose")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--retry-seconds", options.retry_seconds,
                 "after a write error, try a new file this often")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--compression", options.compression,
                 "compress each chunk of the files: none, lz4 (fast) or zstd (smaller); every "
                 "MCAP reader of this project and Foxglove read all three")
      ->check(CLI::IsMember(uavslam::io::mcap_compression_names()))
      ->capture_default_str();
  app.add_option("--dump", options.dump,
                 "list an MCAP file's channels (topic, type, messages, first/last time) and "
                 "whether it is complete, then exit (1 if damaged)")
      ->check(CLI::ExistingFile);
  if (const auto code = uavslam::process::parse_command_line(app, argc, argv)) return *code;
  uavslam::process::install_stop_handler();
  return uavslam::process::run_node("recorder", [&] {
    if (!options.dump.empty()) return uavslam::dump(options.dump);
    if (const auto section = uavslam::process::apply_node_config(app, node, "recorder")) {
      uavslam::apply_own_config(app, *section, options);
    }
    options.topics = uavslam::without_duplicates(options.topics);
    uavslam::RecorderNode recorder(node, options);
    return recorder.run();
  });
}
