#include "LogInput.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <variant>

#include "SimulatedFlight.hpp"
#include "dds/Conversions.hpp"
#include "dds/MessageScanGeometry.hpp"
#include "dds/RecordedMessageStream.hpp"
#include "dds/SimulatedSensorMessages.hpp"
#include "dds/Topics.hpp"
#include "io/CarmenSamples.hpp"
#include "io/CarmenScanStream.hpp"
#include "io/FileError.hpp"
#include "io/McapReader.hpp"

namespace uavslam::cli {
namespace {

// Counting a log's scan lines costs a quick read; the progress bar then shows the time left.
std::size_t count_carmen_scans(const std::string& path) {
  std::ifstream in(path);
  std::size_t scans = 0;
  for (std::string line; std::getline(in, line);) {
    scans += line.rfind("FLASER ", 0) == 0 || line.rfind("ROBOTLASER1 ", 0) == 0;
  }
  return scans;
}

class StampRange {
 public:
  void add(double t) {
    first_ = std::min(first_, t);
    last_ = std::max(last_, t);
  }
  double seconds() const { return last_ > first_ ? last_ - first_ : 0.0; }

 private:
  double first_ = std::numeric_limits<double>::infinity();
  double last_ = -std::numeric_limits<double>::infinity();
};

class CarmenInput : public LogInput {
 public:
  CarmenInput(const std::string& path, HeadingJitter jitter)
      : stream_(path), expected_(count_carmen_scans(path)), jitter_(jitter), random_(jitter.seed) {}

  std::optional<LogEvent> next() override {
    if (pending_.empty()) fill();
    if (pending_.empty()) return std::nullopt;
    LogEvent event = std::move(pending_.front());
    pending_.pop_front();
    return event;
  }
  std::size_t expected_scans() const override { return expected_; }
  std::size_t malformed() const override { return stream_.malformed_lines(); }
  std::vector<std::string> take_problems() override { return stream_.take_new_problems(); }
  double data_seconds() const override { return stamps_.seconds(); }
  std::optional<io::NoReturnCode> no_return_code() const override {
    return stream_.flaser_no_return();
  }

 private:
  // The three events of one scan: its heading, its odometry position, the scan.
  void fill() {
    std::optional<io::TimedCarmenScan> timed = stream_.next();
    if (!timed) return;
    stamps_.add(timed->scan.ipc_timestamp);
    io::CarmenSamples samples = sensor_.samples_of(*timed, jitter());
    LogEvent imu(LogEvent::Kind::Imu);
    imu.imu = samples.orientation;
    LogEvent odometry(LogEvent::Kind::Odometry);
    odometry.odometry = samples.odometry;
    LogEvent scan(LogEvent::Kind::Scan);
    scan.scan = std::move(samples.scan);
    scan.output_stamp = timed->scan.ipc_timestamp;
    scan.start_hint = samples.odometry.position;
    pending_.push_back(std::move(imu));
    pending_.push_back(std::move(odometry));
    pending_.push_back(std::move(scan));
  }

  double jitter() {
    if (jitter_.amplitude <= 0.0) return 0.0;
    return std::uniform_real_distribution<double>(-jitter_.amplitude, jitter_.amplitude)(random_);
  }

  io::CarmenScanStream stream_;
  std::size_t expected_;
  HeadingJitter jitter_;
  std::mt19937 random_;
  io::CarmenSensor sensor_{io::CarmenBody::Robot};
  std::deque<LogEvent> pending_;
  StampRange stamps_;
};

// IMU samples up to each scan's stamp come before the scan, as on the vehicle.
class SimulatedInput : public LogInput {
 public:
  explicit SimulatedInput(std::shared_ptr<const SensorLog> log) : log_(std::move(log)) {}

  std::optional<LogEvent> next() override {
    if (scan_ >= log_->scans.size()) return std::nullopt;
    const Scan& scan = log_->scans[scan_];
    if (imu_ < log_->imu.size() && log_->imu[imu_].stamp <= scan.stamp) {
      LogEvent event(LogEvent::Kind::Imu);
      event.imu = log_->imu[imu_++];
      return event;
    }
    if (velocity_ < log_->velocity.size() && log_->velocity[velocity_].stamp <= scan.stamp) {
      LogEvent event(LogEvent::Kind::Velocity);
      event.velocity = log_->velocity[velocity_++];
      return event;
    }
    LogEvent event(LogEvent::Kind::Scan);
    event.scan = scan;
    event.output_stamp = scan.stamp;
    event.truth = log_->ground_truth[scan_];
    event.start_hint = log_->ground_truth[scan_].position;
    stamps_.add(scan.stamp);
    ++scan_;
    return event;
  }
  std::size_t expected_scans() const override { return log_->scans.size(); }
  double data_seconds() const override { return stamps_.seconds(); }

 private:
  std::shared_ptr<const SensorLog> log_;
  std::size_t scan_ = 0;
  std::size_t imu_ = 0;
  std::size_t velocity_ = 0;
  StampRange stamps_;
};

// What an MCAP recording holds, before reading it: its channels' topics and how many messages
// each has (from the summary; a file without one, cut short, is walked once without decoding).
struct McapContents {
  std::map<std::string, std::uint64_t> messages;  // by topic
  bool counts_known = false;
};

McapContents survey_mcap(const std::string& path) {
  McapContents contents;
  io::McapIndexedReader indexed(path);
  if (indexed.has_summary()) {
    for (const auto& [id, channel] : indexed.channels()) {
      std::uint64_t count = 0;
      if (indexed.statistics()) {
        const auto& counts = indexed.statistics()->channel_message_counts;
        const auto found = counts.find(id);
        count = found == counts.end() ? 0 : found->second;
      }
      contents.messages[channel.topic] += count;
    }
    contents.counts_known = indexed.statistics().has_value();
    return contents;
  }
  io::McapStreamReader stream(path);
  io::mcap::Message message;
  while (stream.next(message)) ++contents.messages[stream.channels().at(message.channel_id).topic];
  for (const auto& [id, channel] : stream.channels()) contents.messages[channel.topic] += 0;
  if (contents.messages.empty() && !stream.report().complete) {
    throw io::file_error(path, stream.report().problem);
  }
  contents.counts_known = true;
  return contents;
}

std::string channel_list(const McapContents& contents) {
  std::string topics;
  for (const auto& [topic, count] : contents.messages)
    topics += (topics.empty() ? "" : ", ") + topic;
  return topics.empty() ? "none" : topics;
}

// The named vehicle's prefix "V/" (dds::topic_name); without a name, "" when the file has a bare
// `scan` channel, else the prefix of its single "V/scan" one.
std::string vehicle_prefix(const std::string& path, const McapContents& contents,
                           const std::string& vehicle) {
  const std::string scan = dds::kScanTopic;
  if (!vehicle.empty()) {
    const std::string prefix = vehicle + "/";
    if (contents.messages.count(prefix + scan)) return prefix;
    throw io::file_error(path, "no " + prefix + scan + " channel for --vehicle " + vehicle +
                                   " (channels: " + channel_list(contents) + ")");
  }
  if (contents.messages.count(scan)) return "";
  std::vector<std::string> prefixes;
  for (const auto& [topic, count] : contents.messages) {
    if (topic.size() > scan.size() + 1 &&
        topic.compare(topic.size() - scan.size() - 1, std::string::npos, "/" + scan) == 0) {
      prefixes.push_back(topic.substr(0, topic.size() - scan.size()));
    }
  }
  if (prefixes.size() == 1) return prefixes.front();
  if (prefixes.empty()) {
    throw io::file_error(
        path, "no scan channel (channels: " + channel_list(contents) + "): nothing to map");
  }
  throw io::file_error(path, "several vehicles' scans (channels: " + channel_list(contents) +
                                 "): choose one with --vehicle");
}

class McapInput : public LogInput {
 public:
  McapInput(const std::string& path, std::shared_ptr<const ScanGeometry> geometry,
            const std::string& prefix, std::size_t expected)
      : stream_(path, {prefix + dds::kScanTopic, prefix + dds::kImuTopic,
                       prefix + dds::kVelocityTopic, prefix + dds::kGroundTruthTopic}),
        geometry_(std::move(geometry)),
        expected_(expected) {}

  std::optional<LogEvent> next() override {
    while (ready_.empty() && !ended_) read_one();
    if (ready_.empty()) return std::nullopt;
    LogEvent event = std::move(ready_.front());
    ready_.pop_front();
    return event;
  }
  std::size_t expected_scans() const override { return expected_; }
  std::size_t malformed() const override { return stream_.malformed() + stream_.skipped(); }
  std::vector<std::string> take_problems() override { return stream_.take_new_problems(); }
  double data_seconds() const override { return stamps_.seconds(); }
  std::string damage() const override { return stream_.damage(); }

 private:
  // One message into the events; a scan waits for the next message, which may be its truth.
  void read_one() {
    std::optional<dds::RecordedMessage> message = stream_.next();
    if (!message) {
      release_scan();
      ended_ = true;
      return;
    }
    if (const auto* imu = std::get_if<msg::Imu>(&message->sample)) {
      release_scan();
      LogEvent event(LogEvent::Kind::Imu);
      event.imu = dds::from_msg(*imu);
      ready_.push_back(std::move(event));
    } else if (const auto* velocity =
                   std::get_if<msg::TwistWithCovarianceStamped>(&message->sample)) {
      release_scan();
      LogEvent event(LogEvent::Kind::Velocity);
      event.velocity = dds::from_msg(*velocity);
      ready_.push_back(std::move(event));
    } else if (const auto* scan = std::get_if<msg::LaserScan>(&message->sample)) {
      release_scan();
      take_scan(*scan);
    } else if (const auto* pose = std::get_if<msg::PoseWithCovarianceStamped>(&message->sample)) {
      take_truth(dds::from_msg(*pose));
    }
  }

  void take_scan(const msg::LaserScan& message) {
    LogEvent event(LogEvent::Kind::Scan);
    event.scan = dds::from_msg(message, geometry_ ? geometry_ : geometries_.for_message(message));
    event.output_stamp = event.scan.stamp;
    stamps_.add(event.scan.stamp);
    scan_ = std::move(event);
    if (truth_ && same_stamp(truth_->stamp, scan_->scan.stamp)) {
      attach_truth(*truth_);
      release_scan();
    }
    truth_.reset();
  }

  void take_truth(const Pose& truth) {
    if (scan_ && same_stamp(truth.stamp, scan_->scan.stamp)) {
      attach_truth(truth);
      release_scan();
      return;
    }
    release_scan();
    truth_ = truth;
  }

  void attach_truth(const Pose& truth) {
    scan_->truth = truth;
    scan_->start_hint = truth.position;
  }

  void release_scan() {
    if (scan_) ready_.push_back(std::move(*scan_));
    scan_.reset();
  }

  static bool same_stamp(double a, double b) { return std::abs(a - b) < 1e-6; }

  dds::RecordedMessageStream stream_;
  std::shared_ptr<const ScanGeometry> geometry_;
  dds::MessageScanGeometry geometries_;
  std::size_t expected_;
  std::deque<LogEvent> ready_;
  std::optional<LogEvent> scan_;  // the last scan read, until its truth or another message comes
  std::optional<Pose> truth_;     // a truth read before its scan
  bool ended_ = false;
  StampRange stamps_;
};

}  // namespace

std::unique_ptr<LogInput> open_mcap_input(const std::string& path,
                                          std::shared_ptr<const ScanGeometry> geometry,
                                          const std::string& vehicle) {
  const McapContents contents = survey_mcap(path);
  const std::string prefix = vehicle_prefix(path, contents, vehicle);
  const std::string imu = prefix + dds::kImuTopic;
  const std::uint64_t scans = contents.messages.at(prefix + dds::kScanTopic);
  if (contents.messages.count(imu) == 0) {
    throw io::file_error(path, "its " + std::to_string(scans) + " scans (channel " + prefix +
                                   dds::kScanTopic + ") come with no " + imu +
                                   " channel: nothing to orient them (the pipeline takes each "
                                   "scan's orientation from the IMU)");
  }
  return std::make_unique<McapInput>(path, std::move(geometry), prefix,
                                     contents.counts_known ? scans : 0);
}

std::unique_ptr<LogInput> open_carmen_input(const std::string& path, HeadingJitter jitter) {
  return std::make_unique<CarmenInput>(path, jitter);
}

std::unique_ptr<LogInput> open_simulated_input(std::shared_ptr<const SensorLog> log) {
  return std::make_unique<SimulatedInput>(std::move(log));
}

}  // namespace uavslam::cli
