// recorder: subscribes `scan` and `imu` (sensor QoS) and writes every sample it receives, as the
// CDR bytes its PubSubType serialises, to a sample log (the format: src/io/SampleLog.hpp). A
// writer thread owns the file: the DDS threads only serialise and queue, so a slow disk costs
// counted drops, never a stalled reader. `--dump FILE` prints what a log holds.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <deque>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <thread>

#include <msg/ImuPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>
#include <CLI/CLI.hpp>

#include "common/HandoffQueue.hpp"
#include "common/IncompatibleQos.hpp"
#include "common/NodeOptions.hpp"
#include "common/RunNode.hpp"
#include "common/StopRequest.hpp"
#include "dds/Participant.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"
#include "io/SampleLog.hpp"

namespace uavslam {
namespace {

const std::vector<std::string> kRecordableTopics{dds::kScanTopic, dds::kImuTopic};

struct RecorderOptions {
  std::string out = "out/recording.uavlog";
  std::vector<std::string> topics = kRecordableTopics;
  int queue_capacity = 4000;  // samples: ~17 s of scan (40 Hz) + imu (200 Hz)
  std::string dump;
};

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
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

// Per topic; the DDS thread counts what arrives, the writer thread what reaches the file.
struct TopicCounts {
  std::string topic;
  std::atomic<std::uint64_t> received{0};
  std::atomic<std::uint64_t> dropped{0};  // queue full, or not serialisable
  std::uint64_t written = 0;
};

class RecorderNode {
 public:
  RecorderNode(const process::NodeOptions& node, const RecorderOptions& o)
      : participant_(node.domain, process::profiles_path(node), node.participant_profile,
                     "recorder"),
        log_(create_log(o.out)),
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
    }
  }
  ~RecorderNode() { finish(); }

  int run() {
    writer_ = std::thread([this] { write_loop(); });
    std::cerr << "recorder: recording " << topic_list() << " to " << log_.path() << " (domain "
              << participant_.domain_id() << ")\n";
    std::size_t scan_writers = 0, imu_writers = 0;
    while (!process::stop_requested() && !writer_failed_) {
      if (scans_) watch(*scans_, scan_writers);
      if (imu_) watch(*imu_, imu_writers);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    finish();
    if (writer_error_) std::rethrow_exception(writer_error_);
    print_counts();
    return 0;
  }

 private:
  static io::SampleLogWriter create_log(const std::string& path) {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    std::error_code ignored;  // a failure shows as the writer's FileError naming the path
    if (!parent.empty()) std::filesystem::create_directories(parent, ignored);
    return io::SampleLogWriter(path);
  }

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
    const std::uint16_t channel = log_.add_channel(topic, type->getName());
    // counts_ is indexed by channel id: one new channel per subscribed topic, in order.
    if (channel != counts_.size()) throw std::logic_error("topic '" + topic + "' subscribed twice");
    TopicCounts& counts = counts_.emplace_back();
    counts.topic = topic;
    // Runs on the reader's DDS thread: serialise, queue, count; never touch the file.
    auto on_sample = [this, type, channel, &counts](
                         const typename PubSubType::type& sample,
                         const eprosima::fastdds::dds::SampleInfo& info) {
      ++counts.received;
      io::LogSample received{channel, now_ns(), info.source_timestamp.to_ns(), {}};
      if (!to_cdr(*type, sample, received.payload) || !queue_.push(std::move(received))) {
        ++counts.dropped;
      }
    };
    return std::make_unique<dds::Reader<PubSubType>>(participant_, topic, profile, on_sample);
  }

  // The writer thread: writes what waits, and flushes whenever it has caught up so the file on
  // disk is complete up to the last sample received.
  void write_loop() {
    std::vector<io::LogSample> batch;
    try {
      while (queue_.take_all(batch, std::chrono::milliseconds(100))) {
        for (const io::LogSample& s : batch) {
          log_.write(s.channel, s.receive_time_ns, s.source_time_ns, s.payload.data(),
                     s.payload.size());
          ++counts_[s.channel].written;
        }
        if (!batch.empty()) log_.flush();
      }
    } catch (const std::exception& e) {
      // A full or failing disk is a run-time failure (exit 1), not a configuration error.
      writer_error_ = std::make_exception_ptr(std::runtime_error(e.what()));
      writer_failed_ = true;
      queue_.close();  // from now on every sample counts as dropped
    }
  }

  // Stops the readers first (no more samples), then lets the writer drain the queue and closes
  // the file. Safe to call twice, and from the destructor when run() throws.
  void finish() {
    scans_.reset();
    imu_.reset();
    queue_.close();
    if (writer_.joinable()) writer_.join();
    try {
      log_.close();
    } catch (...) {
      if (!writer_error_) writer_error_ = std::current_exception();
    }
  }

  std::string topic_list() const {
    std::string out;
    for (const TopicCounts& c : counts_) out += (out.empty() ? "" : ", ") + c.topic;
    return out;
  }

  void print_counts() const {
    for (const TopicCounts& c : counts_) {
      std::cerr << "recorder: " << c.topic << ": " << c.received << " received, " << c.written
                << " written, " << c.dropped << " dropped\n";
    }
    std::cerr << "recorder: " << log_.bytes_written() << " bytes in " << log_.path() << "\n";
  }

  dds::Participant participant_;
  io::SampleLogWriter log_;
  process::HandoffQueue<io::LogSample> queue_;
  std::deque<TopicCounts> counts_;  // by channel id; a deque never moves its elements
  std::unique_ptr<dds::Reader<msg::LaserScanPubSubType>> scans_;
  std::unique_ptr<dds::Reader<msg::ImuPubSubType>> imu_;
  std::thread writer_;
  std::atomic<bool> writer_failed_{false};
  std::exception_ptr writer_error_;
};

// --dump: one line per channel, then what stopped the reading if the file is damaged (exit 1).
int dump(const std::string& path) {
  const io::SampleLog log = io::recover_sample_log(path);
  std::printf("%s: %zu samples\n", path.c_str(), log.samples.size());
  for (const io::ChannelSummary& s : io::summarize(log)) {
    const double span = static_cast<double>(s.last_receive_ns - s.first_receive_ns) * 1e-9;
    std::printf("  %-20s %-28s %8llu samples %12llu bytes over %.3f s\n", s.channel.topic.c_str(),
                s.channel.type.c_str(), static_cast<unsigned long long>(s.samples),
                static_cast<unsigned long long>(s.payload_bytes), span);
  }
  if (log.damage.empty()) return 0;
  std::printf("damaged, read up to the damage: %s\n", log.damage.c_str());
  return 1;
}

std::vector<std::string> without_duplicates(const std::vector<std::string>& topics) {
  std::vector<std::string> out;
  for (const std::string& t : topics) {
    if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
  }
  return out;
}

void apply_own_config(const CLI::App& app, const io::YamlReader& section, RecorderOptions& o) {
  section.expect_keys_only({"out", "topics", "queue_capacity"});
  if (process::unset(app, "--out")) o.out = section.get_string_or("out", o.out);
  if (process::unset(app, "--topics") && section.has("topics")) {
    o.topics.clear();
    for (const io::YamlReader& t : section.at("topics").elements()) {
      o.topics.push_back(t.as_choice(kRecordableTopics));
    }
  }
  if (process::unset(app, "--queue-capacity")) {
    o.queue_capacity =
        section.get_int_or("queue_capacity", o.queue_capacity, io::NumberRange::at_least(1));
  }
}

}  // namespace
}  // namespace uavslam

int main(int argc, char** argv) {
  CLI::App app{
      "recorder: subscribes scan and imu and writes every sample (CDR bytes) to a sample log; "
      "--dump FILE prints what a log holds"};
  uavslam::process::NodeOptions node;
  uavslam::RecorderOptions options;
  uavslam::process::add_node_options(app, node);
  app.add_option("--out", options.out, "sample log to write (created or truncated)")
      ->capture_default_str();
  app.add_option("--topics", options.topics, "topics to record, comma-separated")
      ->delimiter(',')
      ->check(CLI::IsMember(uavslam::kRecordableTopics))
      ->capture_default_str();
  app.add_option("--queue-capacity", options.queue_capacity,
                 "samples waiting for the disk before new ones are dropped")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--dump", options.dump,
                 "print a sample log's channels, counts and time spans, then exit")
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
