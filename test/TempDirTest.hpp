// A test fixture with a directory of its own per test (uavslam_<suite>_XXXXXX under the system's
// temporary directory) for the files it writes and reads back; removed after every test, passed
// or failed.
#pragma once

#include <stdlib.h>  // mkdtemp

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <gtest/gtest.h>

namespace uavslam::test {

class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string suite =
        ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name();
    std::string pattern =
        (std::filesystem::temp_directory_path() / ("uavslam_" + suite + "_XXXXXX")).string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr) << pattern;
    dir = pattern;
  }

  // Google Test runs this after a failed SetUp or test body too.
  void TearDown() override {
    if (dir.empty()) return;
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }

  // A file in this test's directory.
  std::string path(const std::string& name) const { return (dir / name).string(); }

  // Writes `text` to the file `name` of this test's directory and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return path(name);
  }

  std::filesystem::path dir;
};

}  // namespace uavslam::test
