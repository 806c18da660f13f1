// What an integration test hears from a real slam_matcher process: its poses and, from its
// status, the last scan it reported on and its counts. Shared by the replay tests.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/PosePubSubTypes.h>

#include "core/Types.hpp"
#include "dds/Conversions.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Topics.hpp"

namespace uavslam::test {

using namespace std::chrono_literals;

// The matcher's counts in its last status.
struct MatcherCounts {
  std::uint64_t received = 0, skipped = 0, accepted = 0, rejected = 0;
  std::uint64_t processed() const { return accepted + rejected; }
};

// What the test hears from the matcher.
class MatcherListener {
 public:
  MatcherListener(int domain, const std::string& vehicle)
      : participant_(domain, dds::default_profiles_path(), "uavslam_loopback", "test"),
        poses_(participant_, dds::topic_name(vehicle, dds::kPoseTopic), "state_reader",
               [this](const msg::PoseWithCovarianceStamped& m,
                      const eprosima::fastdds::dds::SampleInfo&) {
                 std::lock_guard<std::mutex> lock(mutex_);
                 received_.push_back(dds::from_msg(m));
               }),
        status_(participant_, dds::topic_name(vehicle, dds::kMatcherStatusTopic), "status_reader",
                [this](const msg::MatcherStatus& m, const eprosima::fastdds::dds::SampleInfo&) {
                  {
                    std::lock_guard<std::mutex> lock(mutex_);
                    last_scan_ = m.scan_seq();
                    counts_ = {m.scans_received(), m.scans_skipped(), m.scans_accepted(),
                               m.scans_rejected()};
                  }
                  changed_.notify_all();
                }) {}

  bool matched() { return poses_.wait_for_matched(1, 30s) && status_.wait_for_matched(1, 30s); }
  // Waits until the matcher reported on scan `seq` (it may skip scans, never go back).
  bool wait_for_scan(std::uint64_t seq, std::chrono::seconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return last_scan_ && *last_scan_ >= seq; });
  }
  std::vector<Pose> poses() {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }
  MatcherCounts counts() {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<Pose> received_;
  std::optional<std::uint64_t> last_scan_;
  MatcherCounts counts_;
  dds::Participant participant_;
  dds::Reader<msg::PoseWithCovarianceStampedPubSubType> poses_;
  dds::Reader<msg::MatcherStatusPubSubType> status_;
};

}  // namespace uavslam::test
