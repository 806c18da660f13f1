// The recorder process end to end: the test publishes scans and IMU samples on its own domain and
// the real `recorder` writes them to MCAP files. Stopped by SIGTERM it leaves a complete file
// holding every sample, byte for byte what the PubSubType serialises; killed by SIGKILL, a file
// from which every flushed sample is read back; it rolls over to numbered files; and a disk that
// fills (a file size limit, `ulimit -f`, on the process) costs counted samples and exit code 1,
// never the DDS side, and recording resumes in a new file. --compression (or the config's
// `compression`) compresses every chunk.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <msg/ImuPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/TwistPubSubTypes.h>

#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"
#include "dds/IdlSchemas.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "io/McapListing.hpp"
#include "io/McapReader.hpp"
#include "io/RollingMcapWriter.hpp"

namespace uavslam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using testing::ContainsRegex;
using testing::HasSubstr;

// This test's own DDS domains, one per test.
constexpr int kCleanStopDomain = 150;
constexpr int kKilledDomain = 151;
constexpr int kRollOverDomain = 152;
constexpr int kDiskFullDomain = 153;
constexpr int kConfigDomain = 154;
constexpr int kCompressionFlagDomain = 230;
constexpr int kCompressionConfigDomain = 231;
constexpr int kCompressionErrorDomain = 232;
constexpr char kVehicle[] = "rec";

// Polls until `done` holds or `timeout` passes (for conditions only a file or a log shows).
template <typename Condition>
bool eventually(Condition done, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(20ms);
  }
  return true;
}

// The messages a recorder's file holds so far (it may be writing it).
std::uint64_t samples_in(const std::string& path) {
  if (!fs::exists(path)) return 0;
  return io::list_mcap(path).messages;
}

struct StreamedFile {
  std::vector<io::mcap::Message> messages;
  std::map<std::uint16_t, io::mcap::Channel> channels;
  std::map<std::uint16_t, io::mcap::Schema> schemas;
  io::McapReadReport report;
};

StreamedFile stream(const std::string& path) {
  io::McapStreamReader reader(path);
  StreamedFile file;
  io::mcap::Message message;
  while (reader.next(message)) file.messages.push_back(message);
  file.channels = reader.channels();
  file.schemas = reader.schemas();
  file.report = reader.report();
  return file;
}

msg::LaserScan scan_number(std::uint64_t i) {
  msg::LaserScan scan;
  scan.header().seq(i);
  scan.header().frame_id("laser");
  scan.header().vehicle_id(kVehicle);
  scan.header().stamp().sec(static_cast<std::int32_t>(100 + i / 40));
  scan.header().stamp().nanosec(static_cast<std::uint32_t>((i % 40) * 25000000));
  scan.angle_min(-2.356f);
  scan.angle_increment(0.00436f);
  scan.range_max(30.0f);
  std::vector<float> ranges(1080);
  for (std::size_t b = 0; b < ranges.size(); ++b) ranges[b] = 1.0f + 0.001f * float(b + i);
  scan.ranges(ranges);
  return scan;
}

msg::Imu imu_number(std::uint64_t i) {
  msg::Imu imu;
  imu.header().seq(i);
  imu.header().frame_id("imu");
  imu.orientation().w(1.0);
  imu.orientation().z(0.001 * double(i));
  imu.linear_acceleration().z(9.81);
  imu.orientation_covariance()[0] = -1.0;
  return imu;
}

template <typename PubSubType>
typename PubSubType::type decode(const io::mcap::Message& message) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(
      static_cast<std::uint32_t>(message.data.size()));
  std::copy(message.data.begin(), message.data.end(), payload.data);
  payload.length = static_cast<std::uint32_t>(message.data.size());
  typename PubSubType::type sample;
  EXPECT_TRUE(type.deserialize(&payload, &sample));
  return sample;
}

// The per-topic counts the recorder prints when it ends.
struct PrintedCounts {
  std::uint64_t received = 0, written = 0, dropped = 0, lost = 0;
};

PrintedCounts printed_counts(const std::string& log, const std::string& topic) {
  const std::regex line(topic +
                        ": ([0-9]+) received, ([0-9]+) written, ([0-9]+) dropped, ([0-9]+) lost");
  std::smatch m;
  PrintedCounts counts;
  if (!std::regex_search(log, m, line)) {
    ADD_FAILURE() << "no counts of " << topic << " in\n" << log;
    return counts;
  }
  counts.received = std::stoull(m[1]);
  counts.written = std::stoull(m[2]);
  counts.dropped = std::stoull(m[3]);
  counts.lost = std::stoull(m[4]);
  return counts;
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

// The test as the vehicle's sensors: scans and IMU samples on one domain, sent paced as sensors
// send them (scan 40 Hz, IMU 200 Hz; here faster): a BEST_EFFORT burst of 60 samples at once lost
// 2 of them when the host was loaded by the other tests of `ctest -j2`, which no sensor does.
class Sensors {
 public:
  explicit Sensors(int domain)
      : participant_(domain, dds::default_profiles_path(), "uavslam_loopback", "sensors"),
        scans_(participant_, dds::topic_name(kVehicle, dds::kScanTopic), "sensor_writer"),
        imu_(participant_, dds::topic_name(kVehicle, dds::kImuTopic), "sensor_writer"),
        velocity_(participant_, dds::topic_name(kVehicle, dds::kVelocityTopic), "sensor_writer") {}

  // Waits until the recorder's readers have matched us: a BEST_EFFORT sample sent before that is
  // not delivered, so wait for the recorder to say both of its readers have.
  ::testing::AssertionResult matched(const process::ChildProcess& recorder) {
    if (!scans_.wait_for_matched(1, 30s) || !imu_.wait_for_matched(1, 30s) ||
        !velocity_.wait_for_matched(1, 30s)) {
      return ::testing::AssertionFailure() << "no recorder matched\n" << recorder.log();
    }
    const bool said = eventually(
        [&] {
          const std::string text = recorder.log();
          return text.find("rec/scan: 1 writer(s) matched") != std::string::npos &&
                 text.find("rec/imu: 1 writer(s) matched") != std::string::npos &&
                 text.find("rec/velocity: 1 writer(s) matched") != std::string::npos;
        },
        30s);
    if (!said) return ::testing::AssertionFailure() << recorder.log();
    return ::testing::AssertionSuccess();
  }

  // `scans` scans, each after `imu_per_scan` IMU samples, 1 ms apart.
  ::testing::AssertionResult publish(std::uint64_t scans, std::uint64_t imu_per_scan) {
    for (std::uint64_t s = 0; s < scans; ++s) {
      for (std::uint64_t k = 0; k < imu_per_scan; ++k) {
        if (!imu_.write(imu_number(imu_sent_++))) return ::testing::AssertionFailure() << "imu";
        std::this_thread::sleep_for(1ms);
      }
      if (!scans_.write(scan_number(scans_sent_++))) return ::testing::AssertionFailure() << "scan";
      std::this_thread::sleep_for(1ms);
    }
    return ::testing::AssertionSuccess();
  }

  // `count` velocities of the autopilot, 1 ms apart.
  ::testing::AssertionResult publish_velocities(std::uint64_t count) {
    for (std::uint64_t k = 0; k < count; ++k) {
      msg::TwistWithCovarianceStamped m;
      m.header().seq(velocity_sent_);
      m.linear().x(0.1 * double(velocity_sent_++));
      if (!velocity_.write(m)) return ::testing::AssertionFailure() << "velocity";
      std::this_thread::sleep_for(1ms);
    }
    return ::testing::AssertionSuccess();
  }

  std::uint64_t scans_sent() const { return scans_sent_; }
  std::uint64_t imu_sent() const { return imu_sent_; }

 private:
  dds::Participant participant_;
  dds::Writer<msg::LaserScanPubSubType> scans_;
  dds::Writer<msg::ImuPubSubType> imu_;
  dds::Writer<msg::TwistWithCovarianceStampedPubSubType> velocity_;
  std::uint64_t scans_sent_ = 0, imu_sent_ = 0, velocity_sent_ = 0;
};

class Recorder : public test::ProcessTest {
 protected:
  process::ChildProcess start(int domain, const std::vector<std::string>& flags) {
    std::vector<std::string> extra{"--vehicle", kVehicle};
    extra.insert(extra.end(), flags.begin(), flags.end());
    return process::ChildProcess(node_argv("recorder", domain, extra), log_path("recorder"));
  }

  struct Dumped {
    int exit_code = -1;
    std::string output;
  };

  // `recorder --dump file`, to its end.
  Dumped dump(const std::string& file) {
    process::ChildProcess dumped({binary("recorder"), "--dump", file}, path("dump.log"));
    EXPECT_TRUE(dumped.wait(30s));
    return {dumped.exit_code(), dumped.log()};
  }
};

TEST_F(Recorder, RecordsEveryScanAndImuSampleAndStopsCleanly) {
  constexpr std::uint64_t kBatches = 10, kScansPerBatch = 10, kImuPerScan = 5;
  const std::string file = path("flight_000.mcap");
  process::ChildProcess recorder =
      start(kCleanStopDomain, {"--out", path("flight.mcap"), "--flush-seconds", "0.2"});
  ASSERT_TRUE(recorder.started());
  Sensors sensors(kCleanStopDomain);
  ASSERT_TRUE(sensors.matched(recorder));

  // A batch at a time, each waited for in the file (flushed every 0.2 s).
  for (std::uint64_t batch = 0; batch < kBatches; ++batch) {
    ASSERT_TRUE(sensors.publish(kScansPerBatch, kImuPerScan));
    const std::uint64_t expected = sensors.scans_sent() + sensors.imu_sent();
    ASSERT_TRUE(eventually([&] { return samples_in(file) >= expected; }, 30s))
        << "batch " << batch << ": " << samples_in(file) << " of " << expected << " recorded\n"
        << recorder.log();
  }
  // The autopilot's velocity, where the vehicle has one, is recorded as well.
  ASSERT_TRUE(sensors.publish_velocities(10));
  ASSERT_TRUE(eventually([&] { return samples_in(file) >= 610; }, 30s)) << recorder.log();
  EXPECT_EQ(recorder.stop(10s, SIGTERM), 0) << recorder.log();
  EXPECT_THAT(recorder.log(),
              HasSubstr("rec/scan: 100 received, 100 written, 0 dropped, 0 lost to write errors"));
  EXPECT_THAT(recorder.log(),
              HasSubstr("rec/imu: 500 received, 500 written, 0 dropped, 0 lost to write errors"));
  EXPECT_THAT(
      recorder.log(),
      HasSubstr("rec/velocity: 10 received, 10 written, 0 dropped, 0 lost to write errors"));
  EXPECT_EQ(io::rolled_files(path("flight.mcap")), std::vector<std::string>{file});

  // Complete (SIGTERM closed it: summary and Footer), in the recording conventions.
  io::McapIndexedReader indexed(file);
  ASSERT_TRUE(indexed.has_summary()) << indexed.summary_problem();
  ASSERT_EQ(indexed.channels().size(), 3u);
  std::map<std::string, std::uint16_t> channel_of;
  for (const auto& [id, channel] : indexed.channels()) {
    channel_of[channel.topic] = id;
    EXPECT_EQ(channel.message_encoding, "cdr");
    const io::mcap::Schema& schema = indexed.schemas().at(channel.schema_id);
    EXPECT_EQ(schema.encoding, "omgidl");
    EXPECT_EQ(channel.metadata.at("dds_type"), schema.name);
    EXPECT_EQ(std::optional<std::string>(schema.data), dds::idl_schema(schema.name));
  }
  ASSERT_EQ(channel_of.size(), 3u);
  EXPECT_EQ(indexed.schemas().at(indexed.channels().at(channel_of["rec/scan"]).schema_id).name,
            "uavslam::msg::LaserScan");
  EXPECT_EQ(indexed.schemas().at(indexed.channels().at(channel_of["rec/imu"]).schema_id).name,
            "uavslam::msg::Imu");
  EXPECT_EQ(indexed.schemas().at(indexed.channels().at(channel_of["rec/velocity"]).schema_id).name,
            "uavslam::msg::TwistWithCovarianceStamped");

  std::vector<io::mcap::Message> scans, imu, velocities;
  const io::McapReadReport report = indexed.read_messages(0, [&](const io::mcap::Message& m) {
    (m.channel_id == channel_of["rec/scan"]  ? scans
     : m.channel_id == channel_of["rec/imu"] ? imu
                                             : velocities)
        .push_back(m);
    EXPECT_GT(m.publish_time, 0u);
    EXPECT_LE(m.publish_time, m.log_time) << "one host, one clock";
    return true;
  });
  EXPECT_TRUE(report.complete) << report.problem;
  ASSERT_EQ(scans.size(), kBatches * kScansPerBatch);
  ASSERT_EQ(imu.size(), kBatches * kScansPerBatch * kImuPerScan);
  for (std::uint64_t i : {std::uint64_t{0}, std::uint64_t{57}, std::uint64_t{99}}) {
    EXPECT_TRUE(decode<msg::LaserScanPubSubType>(scans[i]) == scan_number(i)) << i;
    EXPECT_EQ(scans[i].sequence, i);
  }
  EXPECT_TRUE(decode<msg::ImuPubSubType>(imu[321]) == imu_number(321));
  ASSERT_EQ(velocities.size(), 10u);
  EXPECT_DOUBLE_EQ(decode<msg::TwistWithCovarianceStampedPubSubType>(velocities[7]).linear().x(),
                   0.7);

  // --dump lists it for people.
  const Dumped listed = dump(file);
  EXPECT_EQ(listed.exit_code, 0) << listed.output;
  EXPECT_THAT(listed.output, HasSubstr("610 messages on 3 channels"));
  EXPECT_THAT(listed.output, ContainsRegex("rec/scan +uavslam::msg::LaserScan +100 messages"));
  EXPECT_THAT(listed.output, HasSubstr("\ncomplete\n"));
}

TEST_F(Recorder, AKilledRecorderLeavesEveryFlushedSampleReadable) {
  const std::string file = path("killed_000.mcap");
  process::ChildProcess recorder =
      start(kKilledDomain, {"--out", path("killed.mcap"), "--flush-seconds", "0.2"});
  Sensors sensors(kKilledDomain);
  ASSERT_TRUE(sensors.matched(recorder));
  ASSERT_TRUE(sensors.publish(50, 2));
  ASSERT_TRUE(eventually([&] { return samples_in(file) >= 150; }, 30s))
      << samples_in(file) << " of 150 flushed\n"
      << recorder.log();
  EXPECT_EQ(recorder.stop(0s, SIGKILL), 128 + SIGKILL);

  const StreamedFile read = stream(file);
  EXPECT_FALSE(read.report.complete) << "no summary: the recorder never closed it";
  EXPECT_EQ(read.messages.size(), 150u) << read.report.problem;
  EXPECT_EQ(read.channels.size(), 2u);
  std::uint64_t scans = 0;
  for (const io::mcap::Message& m : read.messages) {
    if (read.channels.at(m.channel_id).topic != "rec/scan") continue;
    EXPECT_TRUE(decode<msg::LaserScanPubSubType>(m) == scan_number(scans)) << scans;
    ++scans;
  }
  EXPECT_EQ(scans, 50u);

  const Dumped listed = dump(file);
  EXPECT_EQ(listed.exit_code, 1) << listed.output;
  EXPECT_THAT(listed.output, HasSubstr("150 messages on 2 channels"));
  EXPECT_THAT(listed.output, ContainsRegex("\ndamaged: stopped at byte [0-9]+: "));
}

TEST_F(Recorder, RollsOverToNumberedFilesThatEachStandAlone) {
  const std::string base = path("rolled.mcap");
  process::ChildProcess recorder = start(kRollOverDomain, {"--out", base, "--max-file-mb", "0.05"});
  Sensors sensors(kRollOverDomain);
  ASSERT_TRUE(sensors.matched(recorder));
  ASSERT_TRUE(sensors.publish(100, 1));  // ~4.4 KB a scan: ten files of 50 KiB
  EXPECT_EQ(recorder.stop(10s, SIGTERM), 0) << recorder.log();
  EXPECT_THAT(recorder.log(),
              HasSubstr("rec/scan: 100 received, 100 written, 0 dropped, 0 lost to write errors"));

  const std::vector<std::string> files = io::rolled_files(base);
  ASSERT_GE(files.size(), 8u) << recorder.log();
  EXPECT_EQ(files.front(), path("rolled_000.mcap"));
  std::uint64_t scans = 0, imu = 0;
  for (const std::string& file : files) {
    const io::McapListing listing = io::list_mcap(file);
    EXPECT_TRUE(listing.report.complete) << file << ": " << listing.report.problem;
    EXPECT_EQ(listing.channels.size(), 3u) << "every file declares every channel: " << file;
    EXPECT_LE(fs::file_size(file), 60000u) << file;
    scans += io::messages_on(listing, "rec/scan");
    imu += io::messages_on(listing, "rec/imu");
  }
  EXPECT_EQ(scans, 100u);
  EXPECT_EQ(imu, 100u);
  EXPECT_THAT(recorder.log(), HasSubstr("recording to " + path("rolled_001.mcap")));
}

// The recorder under a file size limit of 2 MiB (root ignores file permissions, not this): its
// first file fills, writes fail with EFBIG (SIGXFSZ ignored, as a full disk fails with ENOSPC).
TEST_F(Recorder, AFullDiskCostsCountedSamplesNotTheFlightAndRecordingResumes) {
  const std::string base = path("full.mcap");
  std::vector<std::string> argv{"/bin/bash", "-c", "trap '' XFSZ; ulimit -f 2048 && exec \"$@\"",
                                "limited"};
  const std::vector<std::string> recorder_argv = node_argv(
      "recorder", kDiskFullDomain,
      {"--vehicle", kVehicle, "--out", base, "--flush-seconds", "0.1", "--retry-seconds", "1"});
  argv.insert(argv.end(), recorder_argv.begin(), recorder_argv.end());
  process::ChildProcess recorder(argv, log_path("recorder"));
  Sensors sensors(kDiskFullDomain);
  ASSERT_TRUE(sensors.matched(recorder));

  // ~4.4 KB a scan: about 480 fill the first file.
  const auto said = [&](const std::string& text) {
    return recorder.log().find(text) != std::string::npos;
  };
  for (int batch = 0; batch < 20 && !said("cannot write: File too large"); ++batch) {
    ASSERT_TRUE(sensors.publish(50, 0));
  }
  ASSERT_TRUE(wait_for_log(recorder, "cannot write: File too large", 10s)) << recorder.log();
  // Samples keep coming (and are lost) until the retry opens the next file.
  for (int batch = 0; batch < 100 && !said("recording resumed"); ++batch) {
    ASSERT_TRUE(sensors.publish(5, 0));
    std::this_thread::sleep_for(100ms);
  }
  ASSERT_TRUE(wait_for_log(recorder, "recording resumed in " + path("full_001.mcap"), 10s))
      << recorder.log();
  ASSERT_TRUE(sensors.publish(20, 0));
  EXPECT_EQ(recorder.stop(10s, SIGTERM), 1) << "samples were lost\n" << recorder.log();

  const std::string log = recorder.log();
  EXPECT_EQ(occurrences(log, "cannot write: File too large"), 1u) << "reported once\n" << log;
  EXPECT_THAT(log, HasSubstr(path("full_000.mcap") + ": cannot write: File too large"));
  const PrintedCounts scans = printed_counts(log, "rec/scan");
  EXPECT_EQ(scans.received, sensors.scans_sent()) << log;
  EXPECT_GT(scans.lost, 0u);
  EXPECT_EQ(scans.written + scans.dropped + scans.lost, scans.received);
  EXPECT_THAT(log, HasSubstr(std::to_string(scans.lost) + " samples lost to write errors"));

  // What the recorder says it wrote is in the files: the cut first one and the resumed one.
  const StreamedFile cut = stream(path("full_000.mcap"));
  EXPECT_FALSE(cut.report.complete);
  const StreamedFile resumed = stream(path("full_001.mcap"));
  EXPECT_TRUE(resumed.report.complete) << resumed.report.problem;
  EXPECT_EQ(cut.messages.size() + resumed.messages.size(), scans.written);
  ASSERT_FALSE(cut.messages.empty());
  ASSERT_FALSE(resumed.messages.empty());
  EXPECT_GT(resumed.messages.front().sequence, cut.messages.back().sequence + 1)
      << "the lost samples are a gap in the sequence";
  EXPECT_EQ(resumed.messages.back().sequence, scans.received - scans.dropped - 1);
}

TEST_F(Recorder, AnUnknownConfigKeyIsNamedAndRefused) {
  const std::string config = path("recorder.yaml");
  std::ofstream(config) << "recorder:\n  max_file_mb: 10\n  outt: x.mcap\n";
  process::ChildProcess recorder(node_argv("recorder", kConfigDomain, {"--config", config}),
                                 log_path("recorder"));
  ASSERT_TRUE(recorder.wait(30s));
  EXPECT_EQ(recorder.exit_code(), 2);
  EXPECT_THAT(recorder.log(), HasSubstr("outt"));
}

TEST_F(Recorder, ARecordingThatCannotStartIsAConfigurationError) {
  const std::string blocker = write("not_a_dir", "x");
  process::ChildProcess recorder(
      node_argv("recorder", kConfigDomain, {"--out", blocker + "/flight.mcap"}),
      log_path("recorder"));
  ASSERT_TRUE(recorder.wait(30s));
  EXPECT_EQ(recorder.exit_code(), 2);
  EXPECT_THAT(recorder.log(), HasSubstr(blocker + "/flight_000.mcap"));
}

// --compression: every chunk of the file compressed as asked, the flag winning over the config.
class RecorderCompression : public Recorder {
 protected:
  // Records 20 scans and 40 IMU samples with `flags` and returns the one file's chunk
  // compressions (one entry per chunk).
  std::vector<std::string> record(int domain, const std::vector<std::string>& flags) {
    const std::string base = path("packed.mcap");
    std::vector<std::string> all{"--out", base, "--flush-seconds", "0.2"};
    all.insert(all.end(), flags.begin(), flags.end());
    process::ChildProcess recorder = start(domain, all);
    Sensors sensors(domain);
    EXPECT_TRUE(sensors.matched(recorder));
    EXPECT_TRUE(sensors.publish(20, 2));
    EXPECT_TRUE(eventually([&] { return samples_in(path("packed_000.mcap")) >= 60; }, 30s))
        << recorder.log();
    EXPECT_EQ(recorder.stop(10s, SIGTERM), 0) << recorder.log();
    const std::string file = path("packed_000.mcap");
    io::McapIndexedReader indexed(file);
    EXPECT_TRUE(indexed.has_summary()) << indexed.summary_problem();
    std::uint64_t scans = 0;
    const io::McapReadReport report = indexed.read_messages(0, [&](const io::mcap::Message& m) {
      if (indexed.channels().at(m.channel_id).topic != "rec/scan") return true;
      EXPECT_TRUE(decode<msg::LaserScanPubSubType>(m) == scan_number(scans)) << scans;
      ++scans;
      return true;
    });
    EXPECT_TRUE(report.complete) << report.problem;
    EXPECT_EQ(scans, 20u);
    const Dumped listed = dump(file);
    EXPECT_EQ(listed.exit_code, 0) << listed.output;
    EXPECT_THAT(listed.output, HasSubstr("60 messages on 3 channels"));
    std::vector<std::string> compressions;
    for (const io::mcap::ChunkIndex& index : indexed.chunk_indexes()) {
      compressions.push_back(index.compression);
    }
    return compressions;
  }
};

TEST_F(RecorderCompression, TheFlagWinsOverTheConfig) {
  const std::string config = write("recorder.yaml", "recorder:\n  compression: lz4\n");
  const auto compressions =
      record(kCompressionFlagDomain, {"--config", config, "--compression", "zstd"});
  ASSERT_FALSE(compressions.empty());
  EXPECT_THAT(compressions, testing::Each(std::string("zstd")));
}

TEST_F(RecorderCompression, TheConfigChoosesWhenNoFlagDoes) {
  const std::string config = write("recorder.yaml", "recorder:\n  compression: lz4\n");
  const auto compressions = record(kCompressionConfigDomain, {"--config", config});
  ASSERT_FALSE(compressions.empty());
  EXPECT_THAT(compressions, testing::Each(std::string("lz4")));
}

TEST_F(RecorderCompression, AnUnknownCompressionIsRefusedWithItsName) {
  process::ChildProcess flagged(
      node_argv("recorder", kCompressionErrorDomain, {"--compression", "gzip"}),
      log_path("flagged"));
  ASSERT_TRUE(flagged.wait(30s));
  EXPECT_EQ(flagged.exit_code(), 2);
  EXPECT_THAT(flagged.log(), HasSubstr("--compression"));
  EXPECT_THAT(flagged.log(), HasSubstr("gzip"));

  const std::string config = write("recorder.yaml", "recorder:\n  compression: gzip\n");
  process::ChildProcess configured(
      node_argv("recorder", kCompressionErrorDomain, {"--config", config}), log_path("configured"));
  ASSERT_TRUE(configured.wait(30s));
  EXPECT_EQ(configured.exit_code(), 2);
  EXPECT_THAT(configured.log(), HasSubstr("recorder.compression"));
  EXPECT_THAT(configured.log(), HasSubstr("gzip"));
  EXPECT_THAT(configured.log(), HasSubstr("'none', 'lz4', 'zstd'"));
}

}  // namespace
}  // namespace uavslam
