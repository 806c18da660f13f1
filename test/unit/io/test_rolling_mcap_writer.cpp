// RollingMcapWriter (src/io/RollingMcapWriter): the recording conventions as a reader sees them,
// roll-over by size and by time, flushing on time and on chunk size, a writer killed mid-stream,
// and write errors (a file size limit, RLIMIT_FSIZE, in a forked child) that cost counted
// messages and a report, never an exception, until a new file opens.
#include <signal.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "TempDirTest.hpp"
#include "io/McapReader.hpp"
#include "io/RollingMcapWriter.hpp"

namespace uavslam::io {
namespace {

using namespace std::chrono_literals;
using Bytes = std::vector<std::uint8_t>;
using Clock = RollingMcapOptions::Clock;
using ::testing::HasSubstr;

const std::string kImuIdl = "module uavslam { module msg { struct Imu { double x; }; }; };\n";
const std::string kScanIdl = "module uavslam { module msg { struct LaserScan { float r; }; }; };\n";

// A clock the test moves by hand.
struct ManualClock {
  Clock::time_point now{};
  std::function<Clock::time_point()> function() {
    return [this] { return now; };
  }
};

struct StreamedFile {
  std::vector<mcap::Message> messages;
  std::map<std::uint16_t, mcap::Channel> channels;
  McapReadReport report;
};

StreamedFile stream(const std::string& path) {
  McapStreamReader reader(path);
  StreamedFile file;
  mcap::Message message;
  while (reader.next(message)) file.messages.push_back(message);
  file.channels = reader.channels();
  file.report = reader.report();
  return file;
}

Bytes payload(std::size_t size, std::uint8_t fill) {
  return Bytes(size, fill);
}

class RollingMcapWriterTest : public test::TempDirTest {
 protected:
  RollingMcapOptions options() {
    RollingMcapOptions o;
    o.clock = clock.function();
    o.sync_on_flush = false;  // the tests read what the OS has; no need to wait for the disk
    o.report = [this](const std::string& line) { reports.push_back(line); };
    return o;
  }

  ManualClock clock;
  std::vector<std::string> reports;
};

TEST(RolledFilePath, NumbersTheFilesOfARecording) {
  EXPECT_EQ(rolled_file_path("out/flight.mcap", 0), "out/flight_000.mcap");
  EXPECT_EQ(rolled_file_path("out/flight.mcap", 2), "out/flight_002.mcap");
  EXPECT_EQ(rolled_file_path("flight", 12), "flight_012.mcap");
  EXPECT_EQ(rolled_file_path("/a.b/flight.mcap", 1234), "/a.b/flight_1234.mcap");
}

TEST_F(RollingMcapWriterTest, WritesTheRecordingConventions) {
  const std::string base = path("flight.mcap");
  {
    RollingMcapWriter writer(base, options());
    const std::size_t imu = writer.add_topic("uav1/imu", "uavslam::msg::Imu", kImuIdl);
    const std::size_t scan = writer.add_topic("uav1/scan", "uavslam::msg::LaserScan", kScanIdl);
    EXPECT_EQ(writer.add_topic("uav1/imu", "uavslam::msg::Imu", kImuIdl), imu);
    EXPECT_THROW(writer.add_topic("uav1/imu", "uavslam::msg::LaserScan", kScanIdl),
                 std::invalid_argument);
    const Bytes a = payload(40, 1), b = payload(4000, 2);
    writer.write(imu, 1'000'000'100, 1'000'000'000, a.data(), a.size());
    writer.write(scan, 1'000'000'200, 1'000'000'050, b.data(), b.size());
    writer.write(imu, 1'000'000'300, 1'000'000'250, a.data(), a.size());
    writer.close();
    EXPECT_EQ(writer.files(), std::vector<std::string>{path("flight_000.mcap")});
    EXPECT_EQ(writer.topics()[imu].written, 2u);
    EXPECT_EQ(writer.topics()[scan].written, 1u);
    EXPECT_EQ(writer.lost(), 0u);
  }
  EXPECT_EQ(rolled_files(base), std::vector<std::string>{path("flight_000.mcap")});

  McapIndexedReader reader(path("flight_000.mcap"));
  ASSERT_TRUE(reader.has_summary()) << reader.summary_problem();
  ASSERT_EQ(reader.schemas().size(), 2u);
  for (const auto& [id, schema] : reader.schemas()) {
    EXPECT_EQ(schema.encoding, "omgidl");
    EXPECT_EQ(schema.data, schema.name == "uavslam::msg::Imu" ? kImuIdl : kScanIdl);
  }
  ASSERT_EQ(reader.channels().size(), 2u);
  std::map<std::string, std::uint16_t> channel_of;
  for (const auto& [id, channel] : reader.channels()) {
    channel_of[channel.topic] = id;
    EXPECT_EQ(channel.message_encoding, "cdr");
    EXPECT_EQ(reader.schemas().at(channel.schema_id).name, channel.metadata.at("dds_type"));
  }
  EXPECT_EQ(reader.channels().at(channel_of["uav1/scan"]).metadata.at("dds_type"),
            "uavslam::msg::LaserScan");
  std::vector<mcap::Message> messages;
  const McapReadReport report = reader.read_messages(0, [&](const mcap::Message& m) {
    messages.push_back(m);
    return true;
  });
  EXPECT_TRUE(report.complete) << report.problem;
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_EQ(messages[1].channel_id, channel_of["uav1/scan"]);
  EXPECT_EQ(messages[1].data, payload(4000, 2));
  EXPECT_EQ(messages[1].log_time, 1'000'000'200u);
  EXPECT_EQ(messages[1].publish_time, 1'000'000'050u);
  EXPECT_EQ(messages[1].sequence, 0u) << "counted per channel";
  EXPECT_EQ(messages[2].sequence, 1u);
}

TEST_F(RollingMcapWriterTest, RollsOverBySizeAndEveryFileStandsAlone) {
  RollingMcapOptions o = options();
  o.max_file_bytes = 20000;
  o.chunk_size = 4000;
  RollingMcapWriter writer(path("flight.mcap"), o);
  const std::size_t scan = writer.add_topic("scan", "uavslam::msg::LaserScan", kScanIdl);
  const Bytes data = payload(1000, 7);
  for (int i = 0; i < 100; ++i) writer.write(scan, 1000 + i, 1000 + i, data.data(), data.size());
  writer.close();

  const std::vector<std::string> files = rolled_files(path("flight.mcap"));
  EXPECT_EQ(files, writer.files());
  ASSERT_GE(files.size(), 5u);
  std::uint32_t next_sequence = 0;
  for (const std::string& file : files) {
    const StreamedFile read = stream(file);
    EXPECT_TRUE(read.report.complete) << file << ": " << read.report.problem;
    ASSERT_EQ(read.channels.size(), 1u) << file;
    EXPECT_EQ(read.channels.begin()->second.topic, "scan");
    EXPECT_FALSE(read.messages.empty()) << file;
    for (const mcap::Message& m : read.messages) EXPECT_EQ(m.sequence, next_sequence++);
    // The data section keeps to the limit; the summary comes on top.
    EXPECT_LE(read.messages.size() * data.size(), 20000u) << file;
  }
  EXPECT_EQ(next_sequence, 100u);
  EXPECT_EQ(writer.topics()[scan].written, 100u);
  ASSERT_EQ(reports.size(), files.size() - 1);
  EXPECT_THAT(reports[0], HasSubstr("flight_000.mcap: closed after"));
  EXPECT_THAT(reports[0], HasSubstr("recording to " + files[1]));
}

TEST_F(RollingMcapWriterTest, RollsOverByTime) {
  RollingMcapOptions o = options();
  o.max_file_duration = 10s;
  RollingMcapWriter writer(path("timed.mcap"), o);
  const std::size_t imu = writer.add_topic("imu", "uavslam::msg::Imu", kImuIdl);
  const Bytes data = payload(10, 3);
  for (int i = 0; i < 10; ++i) {  // one message every 3 s: four to a file
    writer.write(imu, 0, 0, data.data(), data.size());
    clock.now += 3s;
  }
  writer.close();
  ASSERT_EQ(writer.files().size(), 3u);
  EXPECT_EQ(stream(writer.files()[0]).messages.size(), 4u);
  EXPECT_EQ(stream(writer.files()[1]).messages.size(), 4u);
  EXPECT_EQ(stream(writer.files()[2]).messages.size(), 2u);
}

TEST_F(RollingMcapWriterTest, FlushesOnTickAfterTheIntervalAndOnChunkSize) {
  RollingMcapOptions o = options();
  o.flush_interval = 1s;
  o.chunk_size = 10000;
  RollingMcapWriter writer(path("flushed.mcap"), o);
  const std::string file = path("flushed_000.mcap");
  const std::size_t imu = writer.add_topic("imu", "uavslam::msg::Imu", kImuIdl);
  const Bytes small = payload(100, 1), large = payload(20000, 2);
  for (int i = 0; i < 3; ++i) writer.write(imu, 0, 0, small.data(), small.size());
  clock.now += 999ms;
  writer.tick();
  EXPECT_EQ(stream(file).messages.size(), 0u) << "not yet a second since the file opened";
  EXPECT_EQ(writer.topics()[imu].written, 0u);
  clock.now += 1ms;
  writer.tick();
  EXPECT_EQ(stream(file).messages.size(), 3u);
  EXPECT_EQ(writer.topics()[imu].written, 3u);
  writer.write(imu, 0, 0, large.data(), large.size());
  EXPECT_EQ(stream(file).messages.size(), 4u) << "a full chunk is flushed at once";
}

// Writes 50 messages, flushing after the 40th, and dies by SIGKILL without closing anything.
void write_and_get_killed(const std::string& base) {
  RollingMcapOptions o;
  o.sync_on_flush = false;
  RollingMcapWriter writer(base, o);
  const std::size_t imu = writer.add_topic("imu", "uavslam::msg::Imu", kImuIdl);
  const Bytes data = payload(64, 9);
  for (int i = 0; i < 50; ++i) {
    writer.write(imu, 1000 + i, 1000 + i, data.data(), data.size());
    if (i == 39) writer.flush();
  }
  ::raise(SIGKILL);
}

TEST_F(RollingMcapWriterTest, AKilledWriterLeavesEveryFlushedMessageReadable) {
  EXPECT_EXIT(write_and_get_killed(path("killed.mcap")), ::testing::KilledBySignal(SIGKILL), "");
  const StreamedFile read = stream(path("killed_000.mcap"));
  EXPECT_FALSE(read.report.complete);
  ASSERT_EQ(read.messages.size(), 40u) << read.report.problem;
  EXPECT_EQ(read.messages.back().log_time, 1039u);
}

// In a child with a file size limit of 8 KiB (the disk "full"): 1000-byte messages in chunks of
// three until a flush fails, more messages while the retry waits, then the retry's new file.
// Writes what the writer counted and reported to `result`.
void record_past_the_size_limit(const std::string& base, const std::string& result) {
  ::signal(SIGXFSZ, SIG_IGN);  // so write(2) fails with EFBIG instead of killing the process
  const rlimit limit{8192, 8192};
  ::setrlimit(RLIMIT_FSIZE, &limit);
  ManualClock clock;
  std::vector<std::string> reports;
  RollingMcapOptions o;
  o.clock = clock.function();
  o.chunk_size = 3000;
  o.retry_interval = 5s;
  o.sync_on_flush = false;
  o.report = [&](const std::string& line) { reports.push_back(line); };
  RollingMcapWriter writer(base, o);
  const std::size_t scan = writer.add_topic("scan", "uavslam::msg::LaserScan", kScanIdl);
  const Bytes data = payload(1000, 5);
  for (int i = 0; i < 15; ++i) {
    writer.write(scan, 1000 + i, 1000 + i, data.data(), data.size());
    clock.now += 100ms;
  }
  const std::string current_during_outage = writer.current_file();
  clock.now += 5s;
  for (int i = 15; i < 18; ++i) writer.write(scan, 1000 + i, 1000 + i, data.data(), data.size());
  writer.close();
  std::ofstream out(result);
  const RecordedTopic& t = writer.topics()[scan];
  out << t.handed << " " << t.written << " " << t.lost << " " << writer.files().size() << " ["
      << current_during_outage << "]\n";
  for (const std::string& line : reports) out << line << "\n";
  out.close();  // std::exit runs no destructor of this frame
  std::exit(out ? 0 : 1);
}

TEST_F(RollingMcapWriterTest, AWriteErrorCostsCountedMessagesAndRecordingResumesInANewFile) {
  const std::string result = path("result.txt");
  EXPECT_EXIT(record_past_the_size_limit(path("full.mcap"), result), ::testing::ExitedWithCode(0),
              "");
  std::ifstream in(result);
  std::uint64_t handed = 0, written = 0, lost = 0, files = 0;
  std::string current_during_outage;
  in >> handed >> written >> lost >> files >> current_during_outage;
  EXPECT_EQ(current_during_outage, "[]") << "no file open while the retry waits";
  std::vector<std::string> reports;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) reports.push_back(line);
  }
  EXPECT_EQ(handed, 18u);
  EXPECT_GT(lost, 0u);
  EXPECT_EQ(written + lost, handed);
  EXPECT_EQ(files, 2u);
  ASSERT_EQ(reports.size(), 2u) << "the error once, then the resumption";
  EXPECT_THAT(reports[0], HasSubstr(path("full_000.mcap") + ": cannot write: File too large"));
  EXPECT_THAT(reports[0], HasSubstr("tried every 5 s"));
  EXPECT_THAT(reports[1], HasSubstr("recording resumed in " + path("full_001.mcap") + " (" +
                                    std::to_string(lost) + " messages lost)"));

  // What the counts say was written is on disk, no more, no less; the gaps in the sequence are
  // the lost messages.
  const StreamedFile cut = stream(path("full_000.mcap"));
  EXPECT_FALSE(cut.report.complete);
  const StreamedFile resumed = stream(path("full_001.mcap"));
  EXPECT_TRUE(resumed.report.complete) << resumed.report.problem;
  EXPECT_EQ(cut.messages.size() + resumed.messages.size(), written);
  ASSERT_FALSE(resumed.messages.empty());
  EXPECT_EQ(resumed.messages.front().sequence, 15u);
  EXPECT_EQ(resumed.messages.back().sequence, 17u);
}

// In a child with a file size limit of 8 KiB: every message is larger, so every try fails.
void record_while_the_disk_stays_full(const std::string& base, const std::string& result) {
  ::signal(SIGXFSZ, SIG_IGN);
  const rlimit limit{8192, 8192};
  ::setrlimit(RLIMIT_FSIZE, &limit);
  ManualClock clock;
  std::vector<std::string> reports;
  RollingMcapOptions o;
  o.clock = clock.function();
  o.chunk_size = 3000;
  o.sync_on_flush = false;
  o.report = [&](const std::string& line) { reports.push_back(line); };
  RollingMcapWriter writer(base, o);
  const std::size_t scan = writer.add_topic("scan", "uavslam::msg::LaserScan", kScanIdl);
  const Bytes data = payload(10000, 5);
  for (int i = 0; i < 4; ++i) {
    writer.write(scan, 0, 0, data.data(), data.size());
    clock.now += o.retry_interval;
  }
  writer.close();
  std::ofstream out(result);
  out << writer.lost() << " " << writer.files().size() << " " << reports.size() << "\n";
  out.close();
  std::exit(out ? 0 : 1);
}

TEST_F(RollingMcapWriterTest, AnOutageIsReportedOnceAndLeavesNoTrailOfFiles) {
  const std::string result = path("result.txt");
  EXPECT_EXIT(record_while_the_disk_stays_full(path("full.mcap"), result),
              ::testing::ExitedWithCode(0), "");
  std::ifstream in(result);
  std::uint64_t lost = 0, files = 0, reports = 0;
  in >> lost >> files >> reports;
  EXPECT_EQ(lost, 4u);
  EXPECT_EQ(files, 0u) << "no file holds a message";
  EXPECT_EQ(reports, 1u) << "four failed tries, one outage";
  EXPECT_TRUE(std::filesystem::exists(path("full_000.mcap")));
  EXPECT_FALSE(std::filesystem::exists(path("full_001.mcap"))) << "every try took number 000";
}

TEST_F(RollingMcapWriterTest, AFirstFileThatCannotBeCreatedIsAFileErrorNamingIt) {
  const std::string blocker = write("not_a_dir", "x");
  try {
    RollingMcapWriter writer(blocker + "/flight.mcap", options());
    FAIL() << "created a file under a regular file";
  } catch (const FileError& e) {
    EXPECT_THAT(e.what(), HasSubstr(blocker + "/flight_000.mcap"));
  }
}

}  // namespace
}  // namespace uavslam::io
