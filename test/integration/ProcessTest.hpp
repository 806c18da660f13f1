// The fixture of the integration tests that start the real processes: a temporary directory per
// test for their logs and outputs, the built binaries' paths, and the argv of a node on the test's
// own DDS domain. It cleans up after every test, passed or failed.
#pragma once

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "TempDirTest.hpp"
#include "common/ChildProcess.hpp"

namespace uavslam::test {

class ProcessTest : public TempDirTest {
 protected:
  void TearDown() override {
    TempDirTest::TearDown();
    // Processes that were killed leave their shared-memory segments behind.
    if (std::system("fastdds shm clean > /dev/null 2>&1") != 0) {
      ADD_FAILURE() << "fastdds shm clean failed";
    }
  }

  // Where a process started as `name` writes its stdout and stderr.
  std::string log_path(const std::string& name) const { return path(name + ".log"); }

  // A process built by this project.
  static std::string binary(const std::string& name) {
    return std::string(UAVSLAM_BIN_DIR) + "/" + name;
  }

  // The argv of the process `name` on DDS domain `domain`, then `extra`.
  static std::vector<std::string> node_argv(const std::string& name, int domain,
                                            const std::vector<std::string>& extra = {}) {
    std::vector<std::string> argv{binary(name), "--domain", std::to_string(domain)};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return argv;
  }

  // The flags of a sensor process (imu_bridge, lidar_driver) that flies `scenario` at 4x real
  // time from `start_at`, once one subscriber has matched it.
  static std::vector<std::string> sensor_flags(const std::string& scenario,
                                               const std::string& start_at) {
    return {"--scenario", scenario,     "--rate", "4", "--wait-for-subscribers",
            "1",          "--start-at", start_at};
  }

  // Waits until `text` appears in a process's log (processes print what they reach as they go).
  static bool wait_for_log(const process::ChildProcess& process, const std::string& text,
                           std::chrono::seconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      if (process.log().find(text) != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }

  // The flight's start on the system clock, shared by both sensor processes (--start-at), far
  // enough ahead for them to discover the matcher first.
  static std::string shared_start_time() {
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    return std::to_string(std::chrono::duration<double>(now).count() + 3.0);
  }
};

}  // namespace uavslam::test
