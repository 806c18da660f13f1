// The QoS classes on the wire: for each class a writer and a reader of its profiles match across
// two participants on loopback and a sample goes through unchanged; mismatched pairs are reported
// on both sides with the policy at fault; the map class hands a large snapshot to a reader that
// joins after it was published. Intra-process delivery is off, so samples really travel through
// the participant's transports (shared memory here).
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <random>
#include <string>

#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <gtest/gtest.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/MapPointsPubSubTypes.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/OccupancyMapPubSubTypes.h>
#include <msg/PosePubSubTypes.h>

#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Writer.hpp"

namespace uavslam::dds {
namespace {

using namespace std::chrono_literals;

constexpr auto kDiscovery = 30s;  // discovery is usually ~0.1 s but has taken 3 s here

class PubSub : public testing::Test {
 protected:
  void SetUp() override {
    eprosima::fastrtps::LibrarySettingsAttributes settings;
    settings.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
    eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(settings);
  }
};

msg::Header header(std::uint64_t seq) {
  msg::Header h;
  h.stamp().sec(1700000000);
  h.stamp().nanosec(123456789);
  h.frame_id("map");
  h.seq(seq);
  h.vehicle_id("uav1");
  return h;
}

// Keeps the last sample a reader delivered.
template <typename Sample>
struct LastSample {
  std::mutex mutex;
  std::optional<Sample> sample;
  void operator()(const Sample& s) {
    std::lock_guard<std::mutex> lock(mutex);
    sample = s;
  }
  std::optional<Sample> get() {
    std::lock_guard<std::mutex> lock(mutex);
    return sample;
  }
};

// A writer of <cls>_writer and a reader of <cls>_reader in two participants of `domain`: they
// match with no incompatible QoS on either side, and `sample` arrives equal. A BEST_EFFORT class
// may lose a sample by design, so it may be sent up to 5 times; a RELIABLE class is sent once.
template <typename PubSubType>
void expect_class_delivers(int domain, const std::string& cls,
                           const typename PubSubType::type& sample, bool best_effort = false) {
  using Sample = typename PubSubType::type;
  Participant writer_side(domain, default_profiles_path(), "uavslam_loopback", "writer_side");
  Participant reader_side(domain, default_profiles_path(), "uavslam_loopback", "reader_side");
  const std::string topic = "qos_test/" + cls;
  LastSample<Sample> last;
  Reader<PubSubType> reader(reader_side, topic, cls + "_reader",
                            [&](const Sample& s, const auto&) { last(s); });
  Writer<PubSubType> writer(writer_side, topic, cls + "_writer");
  ASSERT_TRUE(writer.wait_for_matched(1, kDiscovery));
  ASSERT_TRUE(reader.wait_for_matched(1, kDiscovery));

  ASSERT_TRUE(writer.write(sample));
  for (int retry = 0; best_effort && retry < 4 && !reader.wait_for_received(1, 2s); ++retry) {
    ASSERT_TRUE(writer.write(sample));
  }
  ASSERT_TRUE(reader.wait_for_received(1, kDiscovery));
  const std::optional<Sample> got = last.get();
  ASSERT_TRUE(got.has_value());
  EXPECT_TRUE(*got == sample);
  EXPECT_EQ(writer.incompatible_qos_count(), 0u);
  EXPECT_EQ(reader.incompatible_qos_count(), 0u);
}

TEST_F(PubSub, SensorClassDeliversAScan) {
  msg::LaserScan scan;
  scan.header(header(7));
  scan.angle_min(-2.35f);
  scan.angle_increment(0.0044f);
  scan.ranges(std::vector<float>(1080, 4.5f));
  scan.ranges()[17] = 0.25f;
  expect_class_delivers<msg::LaserScanPubSubType>(180, "sensor", scan, true);
}

TEST_F(PubSub, StateClassDeliversAPose) {
  msg::PoseWithCovarianceStamped pose;
  pose.header(header(3));
  pose.position().x(1.5);
  pose.orientation().w(1.0);
  pose.covariance()[0] = 0.01;
  pose.quality(0.9f);
  pose.scan_seq(42);
  expect_class_delivers<msg::PoseWithCovarianceStampedPubSubType>(181, "state", pose);
}

TEST_F(PubSub, MapPointsClassDeliversAKeyframe) {
  msg::MapPoints points;
  points.header(header(1));
  points.keyframe_index(5);
  for (int i = 0; i < 216; ++i) {
    msg::Point32 p;
    p.x(0.1f * static_cast<float>(i));
    p.z(1.0f);
    points.points().push_back(p);
  }
  expect_class_delivers<msg::MapPointsPubSubType>(182, "map_points", points);
}

TEST_F(PubSub, StatusClassDeliversAStatus) {
  msg::MatcherStatus status;
  status.header(header(9));
  status.outcome("error_increased");
  status.iterations(10);
  status.scans_received(100);
  expect_class_delivers<msg::MatcherStatusPubSubType>(183, "status", status);
}

// The map class: a 4 MB snapshot published before any reader exists reaches a reader that joins
// afterwards (TRANSIENT_LOCAL, KEEP_LAST 1), through the writer's flow controller.
TEST_F(PubSub, MapClassDeliversALargeSnapshotToALateJoiner) {
  Participant writer_side(184, default_profiles_path(), "uavslam_loopback", "map_server");
  Writer<msg::OccupancyMapPubSubType> writer(writer_side, "qos_test/map", "map_writer");
  const auto& qos = writer.native().get_qos();
  EXPECT_EQ(qos.publish_mode().kind, eprosima::fastdds::dds::ASYNCHRONOUS_PUBLISH_MODE);
  EXPECT_GT(qos.throughput_controller().bytesPerPeriod, 0u) << "the map writer is flow controlled";
  EXPECT_LT(qos.throughput_controller().bytesPerPeriod, UINT32_MAX);

  msg::OccupancyMap map;
  map.header(header(2));
  map.map_seq(2);
  map.resolution(0.05);
  std::vector<std::uint8_t> blob(4u << 20);
  std::mt19937 random(5);
  for (auto& byte : blob) byte = static_cast<std::uint8_t>(random());
  map.octomap_binary(blob);
  ASSERT_TRUE(writer.write(map));

  Participant reader_side(184, default_profiles_path(), "uavslam_loopback", "ground_station");
  LastSample<msg::OccupancyMap> last;
  Reader<msg::OccupancyMapPubSubType> reader(
      reader_side, "qos_test/map", "map_reader",
      [&](const msg::OccupancyMap& m, const auto&) { last(m); });
  ASSERT_TRUE(reader.wait_for_matched(1, kDiscovery));
  // 4 MB at the controller's rate takes seconds; the bound only stops a hung test.
  ASSERT_TRUE(reader.wait_for_received(1, 90s));
  const std::optional<msg::OccupancyMap> got = last.get();
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->octomap_binary().size(), blob.size());
  EXPECT_TRUE(*got == map);
}

// Both sides of a mismatched pair hear of it, naming the policy, and never match.
template <typename PubSubType>
void expect_incompatible(Participant& writer_side, Participant& reader_side,
                         const std::string& writer_profile, const std::string& reader_profile,
                         const std::string& policy) {
  const std::string topic = "qos_test/" + writer_profile + "_vs_" + reader_profile;
  Reader<PubSubType> reader(reader_side, topic, reader_profile, nullptr);
  Writer<PubSubType> writer(writer_side, topic, writer_profile);
  ASSERT_TRUE(writer.wait_for_incompatible_qos(1, kDiscovery)) << writer_profile;
  ASSERT_TRUE(reader.wait_for_incompatible_qos(1, kDiscovery)) << reader_profile;
  EXPECT_EQ(writer.last_incompatible_policy(), policy);
  EXPECT_EQ(reader.last_incompatible_policy(), policy);
  EXPECT_EQ(writer.matched(), 0u);
  EXPECT_EQ(reader.matched(), 0u);
}

TEST_F(PubSub, IncompatiblePairsAreReportedOnBothSidesWithThePolicy) {
  Participant writer_side(185, default_profiles_path(), "uavslam_loopback", "writer_side");
  Participant reader_side(185, default_profiles_path(), "uavslam_loopback", "reader_side");
  expect_incompatible<msg::PoseWithCovarianceStampedPubSubType>(
      writer_side, reader_side, "sensor_writer", "state_reader", "RELIABILITY");
  expect_incompatible<msg::MatcherStatusPubSubType>(writer_side, reader_side, "state_writer",
                                                    "status_reader", "DURABILITY");
}

}  // namespace
}  // namespace uavslam::dds
