// The recorder process end to end: the test publishes scans and IMU samples on its own domain,
// the real `recorder` writes them to a sample log, stops on SIGTERM, and the log read back holds
// every sample, byte for byte what the PubSubType serialises.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <msg/ImuPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>

#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Topics.hpp"
#include "dds/Writer.hpp"
#include "io/SampleLog.hpp"

namespace uavslam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using testing::HasSubstr;

constexpr int kDomain = 179;  // this test's own DDS domain
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

std::size_t samples_in(const std::string& path) {
  if (!fs::exists(path)) return 0;
  return io::recover_sample_log(path).samples.size();
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
typename PubSubType::type decode(const io::LogSample& sample) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(
      static_cast<std::uint32_t>(sample.payload.size()));
  std::copy(sample.payload.begin(), sample.payload.end(), payload.data);
  payload.length = static_cast<std::uint32_t>(sample.payload.size());
  typename PubSubType::type message;
  EXPECT_TRUE(type.deserialize(&payload, &message));
  return message;
}

using Recorder = test::ProcessTest;

TEST_F(Recorder, RecordsEveryScanAndImuSampleAndStopsCleanly) {
  constexpr std::uint64_t kBatches = 10, kScansPerBatch = 10, kImuPerScan = 5;
  const std::string log_file = path("flight.uavlog");
  process::ChildProcess recorder(
      node_argv("recorder", kDomain, {"--vehicle", kVehicle, "--out", log_file}),
      log_path("recorder"));
  ASSERT_TRUE(recorder.started());

  dds::Participant sensors(kDomain, dds::default_profiles_path(), "uavslam_loopback", "sensors");
  dds::Writer<msg::LaserScanPubSubType> scans(sensors, dds::topic_name(kVehicle, dds::kScanTopic),
                                              "sensor_writer");
  dds::Writer<msg::ImuPubSubType> imu(sensors, dds::topic_name(kVehicle, dds::kImuTopic),
                                      "sensor_writer");
  ASSERT_TRUE(scans.wait_for_matched(1, 30s)) << recorder.log();
  ASSERT_TRUE(imu.wait_for_matched(1, 30s)) << recorder.log();
  // BEST_EFFORT: a sample sent before the recorder's reader has matched us is not delivered, so
  // wait for the recorder to say both of its readers have.
  ASSERT_TRUE(eventually(
      [&] {
        const std::string text = recorder.log();
        return text.find("rec/scan: 1 writer(s) matched") != std::string::npos &&
               text.find("rec/imu: 1 writer(s) matched") != std::string::npos;
      },
      30s))
      << recorder.log();

  // A batch at a time, each waited for in the log (the recorder flushes whenever it catches
  // up), and the samples of a batch paced 1 ms apart as sensors send them (scan 40 Hz, IMU
  // 200 Hz; here 5x faster): a BEST_EFFORT burst of 60 samples at once lost 2 of them when the
  // host was loaded by the other tests of `ctest -j2`, which no sensor does.
  std::uint64_t scan_seq = 0, imu_seq = 0;
  const auto paced = [](bool written) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return written;
  };
  for (std::uint64_t batch = 0; batch < kBatches; ++batch) {
    for (std::uint64_t s = 0; s < kScansPerBatch; ++s) {
      for (std::uint64_t k = 0; k < kImuPerScan; ++k) {
        ASSERT_TRUE(paced(imu.write(imu_number(imu_seq++))));
      }
      ASSERT_TRUE(paced(scans.write(scan_number(scan_seq++))));
    }
    const std::size_t expected = scan_seq + imu_seq;
    ASSERT_TRUE(eventually([&] { return samples_in(log_file) >= expected; }, 30s))
        << "batch " << batch << ": " << samples_in(log_file) << " of " << expected << " recorded\n"
        << recorder.log();
  }
  EXPECT_EQ(recorder.stop(10s), 0) << recorder.log();
  EXPECT_THAT(recorder.log(), HasSubstr("rec/scan: 100 received, 100 written, 0 dropped"));
  EXPECT_THAT(recorder.log(), HasSubstr("rec/imu: 500 received, 500 written, 0 dropped"));

  const io::SampleLog log = io::read_sample_log(log_file);  // complete: SIGTERM flushed it
  ASSERT_EQ(log.channels.size(), 2u);
  const auto channel_of = [&](const io::LogSample& s) {
    for (const io::LogChannel& c : log.channels) {
      if (c.id == s.channel) return c;
    }
    return io::LogChannel{};
  };
  std::vector<const io::LogSample*> scan_samples, imu_samples;
  for (const io::LogSample& s : log.samples) {
    (channel_of(s).topic == "rec/scan" ? scan_samples : imu_samples).push_back(&s);
    EXPECT_GT(s.source_time_ns, 0);
    EXPECT_LE(s.source_time_ns, s.receive_time_ns) << "one host, one clock";
  }
  ASSERT_EQ(scan_samples.size(), kBatches * kScansPerBatch);
  ASSERT_EQ(imu_samples.size(), kBatches * kScansPerBatch * kImuPerScan);
  EXPECT_EQ(channel_of(*scan_samples.front()).type, "uavslam::msg::LaserScan");
  EXPECT_EQ(channel_of(*imu_samples.front()).type, "uavslam::msg::Imu");
  for (std::uint64_t i : {std::uint64_t{0}, std::uint64_t{57}, std::uint64_t{99}}) {
    EXPECT_TRUE(decode<msg::LaserScanPubSubType>(*scan_samples[i]) == scan_number(i)) << i;
  }
  EXPECT_TRUE(decode<msg::ImuPubSubType>(*imu_samples[321]) == imu_number(321));

  // --dump reads it back for people.
  process::ChildProcess dump({binary("recorder"), "--dump", log_file}, path("dump.log"));
  ASSERT_TRUE(dump.wait(30s));
  EXPECT_EQ(dump.exit_code(), 0) << dump.log();
  EXPECT_THAT(dump.log(), HasSubstr("600 samples"));
  EXPECT_THAT(dump.log(), testing::ContainsRegex("rec/scan +uavslam::msg::LaserScan +100 samples"));
}

TEST_F(Recorder, AnUnknownConfigKeyIsNamedAndRefused) {
  const std::string config = path("recorder.yaml");
  std::ofstream(config) << "recorder:\n  outt: x.uavlog\n";
  process::ChildProcess recorder(node_argv("recorder", kDomain, {"--config", config}),
                                 log_path("recorder"));
  ASSERT_TRUE(recorder.wait(30s));
  EXPECT_EQ(recorder.exit_code(), 2);
  EXPECT_THAT(recorder.log(), HasSubstr("outt"));
}

TEST_F(Recorder, DumpOfATruncatedLogPrintsWhatIsThereAndFails) {
  const std::string log_file = path("cut.uavlog");
  {
    io::SampleLogWriter writer(log_file);
    const std::vector<std::uint8_t> payload(64, 1);
    const auto channel = writer.add_channel("rec/imu", "uavslam::msg::Imu");
    writer.write(channel, 1'000'000'000, 999'000'000, payload.data(), payload.size());
    writer.write(channel, 2'000'000'000, 1'999'000'000, payload.data(), payload.size());
    writer.close();
  }
  fs::resize_file(log_file, fs::file_size(log_file) - 10);
  process::ChildProcess dump({binary("recorder"), "--dump", log_file}, path("dump.log"));
  ASSERT_TRUE(dump.wait(30s));
  EXPECT_EQ(dump.exit_code(), 1) << dump.log();
  EXPECT_THAT(dump.log(), HasSubstr("1 samples"));
  EXPECT_THAT(dump.log(), HasSubstr(log_file + ": byte "));
}

}  // namespace
}  // namespace uavslam
