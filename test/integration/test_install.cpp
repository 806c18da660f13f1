// `cmake --install` gives a tree a vehicle runs from (docs/deployment.md "On the vehicle"): the
// processes in bin/, the QoS profiles in qos/ (found there without $UAVSLAM_QOS_FILE), the
// configuration, launch files and systemd units in config/; and the installed launcher runs the
// installed processes.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "ProcessTest.hpp"
#include "common/ChildProcess.hpp"

namespace uavslam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using testing::HasSubstr;

constexpr int kDomain = 193;

using Install = test::ProcessTest;

TEST_F(Install, TheInstalledTreeRunsOnItsOwnProfiles) {
  const std::string prefix = path("opt");
  process::ChildProcess install({UAVSLAM_CMAKE, "--install", UAVSLAM_BUILD_DIR, "--prefix", prefix},
                                path("install.log"));
  ASSERT_TRUE(install.wait(120s));
  ASSERT_EQ(install.exit_code(), 0) << install.log();
  for (const char* file :
       {"bin/uavslam", "bin/slam_matcher", "bin/ground_station", "qos/uavslam_profiles.xml",
        "config/slam.yaml", "config/launch/uav.yaml", "config/systemd/uavslam-uav.service"}) {
    EXPECT_TRUE(fs::exists(fs::path(prefix) / file)) << file;
  }

  // An unknown profile names the file the process loaded: the installed one.
  unsetenv("UAVSLAM_QOS_FILE");
  process::ChildProcess station(
      {prefix + "/bin/ground_station", "--domain", std::to_string(kDomain), "--participant-profile",
       "no_such", "--out", path("gcs")},
      path("station.log"));
  ASSERT_TRUE(station.wait(30s));
  EXPECT_EQ(station.exit_code(), 2) << station.log();
  EXPECT_THAT(station.log(), HasSubstr(prefix + "/qos/uavslam_profiles.xml"));
}

}  // namespace
}  // namespace uavslam
