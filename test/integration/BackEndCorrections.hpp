// The back end's corrections followed through the real processes: what the matcher, the map server
// and the ground station each say of them. Shared by the tests that fly or replay with the back
// end.
#pragma once

#include <cstddef>
#include <fstream>
#include <optional>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/TumFile.hpp"

namespace uavslam::test {

struct FollowedCorrections {
  nlohmann::json summary;     // the ground station's summary.json
  std::size_t keyframes = 0;  // lines of its keyframes.tum
};

// The matcher accepted loops and published corrections; the map server applied at least one and
// at most as many (each message holds every keyframe, so it may fold two that came together into
// one); the ground station received them, its matcher_status counts as many as were published, and
// its keyframes.tum has a line per corrected keyframe. None when a log line or the summary is
// missing (a failure is recorded).
inline std::optional<FollowedCorrections> expect_corrections_followed(
    const std::string& matcher_log, const std::string& map_server_log,
    const std::string& station_out) {
  static const std::regex loops(R"(loops: (\d+) accepted[^;]*; (\d+) corrections published)");
  static const std::regex applied(R"((\d+) corrections from the back end applied)");
  std::smatch m;
  if (!std::regex_search(matcher_log, m, loops)) {
    ADD_FAILURE() << "no loops line in the matcher's log:\n" << matcher_log;
    return std::nullopt;
  }
  EXPECT_GT(std::stoi(m[1]), 0) << matcher_log;
  const int published = std::stoi(m[2]);
  EXPECT_GT(published, 0) << matcher_log;
  if (!std::regex_search(map_server_log, m, applied)) {
    ADD_FAILURE() << "no corrections line in the map server's log:\n" << map_server_log;
    return std::nullopt;
  }
  EXPECT_GE(std::stoi(m[1]), 1) << map_server_log;
  EXPECT_LE(std::stoi(m[1]), published) << map_server_log;

  std::ifstream summary_file(station_out + "/summary.json");
  if (!summary_file) {
    ADD_FAILURE() << "no " << station_out << "/summary.json";
    return std::nullopt;
  }
  FollowedCorrections followed{nlohmann::json::parse(summary_file), 0};
  const nlohmann::json& summary = followed.summary;
  EXPECT_GE(summary["back_end"]["corrections_received"].get<int>(), 1) << summary.dump(2);
  EXPECT_EQ(summary["matcher_status"]["corrections"].get<int>(), published) << summary.dump(2);
  followed.keyframes = io::read_tum(station_out + "/keyframes.tum").size();
  EXPECT_EQ(followed.keyframes, summary["back_end"]["keyframes_corrected"].get<std::size_t>());
  return followed;
}

}  // namespace uavslam::test
