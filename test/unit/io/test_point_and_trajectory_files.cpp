#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/PlyFile.hpp"
#include "io/TumFile.hpp"

namespace uavslam::io {
namespace {

using testing::HasSubstr;
using testing::StartsWith;

// Hands out paths under the test temp dir and removes the files when the test ends.
class FileTest : public testing::Test {
 protected:
  ~FileTest() override {
    for (const std::string& path : paths_) std::remove(path.c_str());
  }

  std::string temp_path(const std::string& name) {
    const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
    paths_.push_back(testing::TempDir() + "uavslam_" + test->name() + "_" + name);
    return paths_.back();
  }

  std::string file_with(const std::string& name, const std::string& bytes) {
    const std::string path = temp_path(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  static std::string bytes_of(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  }

 private:
  std::vector<std::string> paths_;
};

// The message of the FileError `read` throws; fails the test if it throws none.
template <typename Read>
std::string file_error_of(Read read) {
  try {
    read();
  } catch (const FileError& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected a FileError";
  return "";
}

std::string little_endian_bytes(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  std::string bytes;
  for (int i = 0; i < 4; ++i) bytes += static_cast<char>((bits >> (8 * i)) & 0xFF);
  return bytes;
}

std::string little_endian_bytes(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  std::string bytes;
  for (int i = 0; i < 8; ++i) bytes += static_cast<char>((bits >> (8 * i)) & 0xFF);
  return bytes;
}

// ---- TUM trajectories ----

std::vector<Pose> sample_poses() {
  std::vector<Pose> poses(3);
  poses[0].stamp = 1700000000.123456;  // a Unix time, as recorded flights have
  poses[0].position = Vec3(1.234567, -2.5, 0.000001);
  poses[0].orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
  poses[1].stamp = 0.000000001;
  poses[1].position = Vec3(-1000.25, 3.141593, 42.0);
  poses[2].stamp = 12.5;
  poses[2].orientation = Eigen::Quaterniond(-0.5, 0.5, -0.5, 0.5);
  return poses;
}

TEST_F(FileTest, TumRoundTripKeepsValuesToPrintPrecision) {
  const std::string path = temp_path("round_trip.tum");
  const std::vector<Pose> written = sample_poses();
  write_tum(path, written);
  const std::vector<Pose> read = read_tum(path);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_NEAR(read[i].stamp, written[i].stamp, 1e-9);
    EXPECT_LT((read[i].position - written[i].position).norm(), 1e-6);
    EXPECT_LT((read[i].orientation.coeffs() - written[i].orientation.coeffs()).norm(), 1e-8);
  }
}

TEST_F(FileTest, TumLinesAreTimePositionAndXyzwQuaternion) {
  const std::string path = temp_path("layout.tum");
  Pose pose;
  pose.stamp = 1.5;
  pose.position = Vec3(1, 2, 3);
  pose.orientation = Eigen::Quaterniond(0.5, 0.5, 0.5, 0.5);  // w x y z
  write_tum(path, {pose});
  EXPECT_THAT(bytes_of(path),
              HasSubstr("\n1.500000000 1.000000 2.000000 3.000000 0.500000000 0.500000000 "
                        "0.500000000 0.500000000\n"));
}

TEST_F(FileTest, TumReaderSkipsCommentsAndBlankLinesAndNormalises) {
  const std::string path = file_with("comments.tum",
                                     "# timestamp tx ty tz qx qy qz qw\n"
                                     "\n"
                                     "1.0 1 2 3 0 0 0 2   # a trailing comment\r\n"
                                     "\t2.0\t4 5 6 0 0 3 0\n");
  const std::vector<Pose> poses = read_tum(path);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].stamp, 1.0);
  EXPECT_EQ(poses[0].position, Vec3(1, 2, 3));
  EXPECT_TRUE(poses[0].orientation.isApprox(Eigen::Quaterniond::Identity()));
  EXPECT_EQ(poses[1].position, Vec3(4, 5, 6));
  EXPECT_DOUBLE_EQ(poses[1].orientation.z(), 1.0);
}

TEST_F(FileTest, TumWrongNumberCountNamesFileLineAndText) {
  const std::string path = file_with("short.tum", "# header\n1 0 0 0 0 0 0 1\n2 1 2 3 4\n");
  const std::string message = file_error_of([&] { read_tum(path); });
  EXPECT_THAT(message, StartsWith(path + ":3: expected 8 numbers 't x y z qx qy qz qw', got 5"));
  EXPECT_THAT(message, HasSubstr("'2 1 2 3 4'"));
}

TEST_F(FileTest, TumNonNumberNamesTheField) {
  const std::string path = file_with("text.tum", "1 0 0 0 0 0 0 1\n2 0 0 abc 0 0 0 1\n");
  const std::string message = file_error_of([&] { read_tum(path); });
  EXPECT_THAT(message, StartsWith(path + ":2: 'abc' is not a finite number (field z)"));
}

TEST_F(FileTest, TumRejectsNonFiniteNumbers) {
  const std::string path = file_with("nan.tum", "1 nan 0 0 0 0 0 1\n");
  EXPECT_THAT(file_error_of([&] { read_tum(path); }), StartsWith(path + ":1: 'nan'"));
}

TEST_F(FileTest, TumZeroQuaternionIsAnError) {
  const std::string path = file_with("zero.tum", "1 0 0 0 0 0 0 1\n\n3 1 2 3 0 0 0 0\n");
  EXPECT_THAT(file_error_of([&] { read_tum(path); }),
              StartsWith(path + ":3: zero quaternion is not a rotation: '3 1 2 3 0 0 0 0'"));
}

TEST_F(FileTest, TumMissingFileNamesPathAndReason) {
  const std::string path = temp_path("does_not_exist.tum");
  EXPECT_EQ(file_error_of([&] { read_tum(path); }),
            path + ": cannot open: No such file or directory");
}

TEST_F(FileTest, TumUnwritablePathNamesPathAndReason) {
  const std::string path = temp_path("no_such_dir/out.tum");
  EXPECT_EQ(file_error_of([&] { write_tum(path, sample_poses()); }),
            path + ": cannot write: No such file or directory");
}

TEST_F(FileTest, FileErrorIsARuntimeError) {
  const std::string path = temp_path("missing.tum");
  EXPECT_THROW(read_tum(path), std::runtime_error);
}

// ---- PLY point clouds ----

const Points kCloud = {Vec3(1.0, -2.5, 0.25), Vec3(1e3, 0.0, -7.0), Vec3(0.1, 0.2, 0.3)};

TEST_F(FileTest, PlyBinaryHasTheExactHeaderAndLittleEndianFloats) {
  const std::string path = temp_path("cloud.ply");
  write_ply(path, kCloud);
  const std::string expected_header =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "comment written by uavslam\n"
      "element vertex 3\n"
      "property float x\n"
      "property float y\n"
      "property float z\n"
      "end_header\n";
  const std::string bytes = bytes_of(path);
  ASSERT_EQ(bytes.size(), expected_header.size() + 3 * 3 * 4);
  EXPECT_EQ(bytes.substr(0, expected_header.size()), expected_header);
  EXPECT_EQ(bytes.substr(expected_header.size(), 4), std::string("\x00\x00\x80\x3f", 4));  // 1.0f
  EXPECT_EQ(bytes.substr(expected_header.size() + 4, 4), little_endian_bytes(-2.5f));
}

TEST_F(FileTest, PlyBinaryRoundTripKeepsFloatPrecision) {
  const std::string path = temp_path("round_trip.ply");
  write_ply(path, kCloud);
  const Points read = read_ply(path);
  ASSERT_EQ(read.size(), kCloud.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_FLOAT_EQ(static_cast<float>(read[i][axis]), static_cast<float>(kCloud[i][axis]));
    }
  }
}

TEST_F(FileTest, PlyWithIntensityAddsAFloatPropertyAfterXyz) {
  const std::string path = temp_path("intensity.ply");
  write_ply(path, kCloud, {10.0f, 20.0f, 30.5f});
  const std::string bytes = bytes_of(path);
  const std::string properties = "property float z\nproperty float intensity\nend_header\n";
  const std::size_t body = bytes.find(properties);
  ASSERT_NE(body, std::string::npos) << bytes;
  const std::size_t start = body + properties.size();
  ASSERT_EQ(bytes.size(), start + 3 * 4 * 4);
  EXPECT_EQ(bytes.substr(start + 12, 4), little_endian_bytes(10.0f));
  EXPECT_EQ(bytes.substr(start + 2 * 16 + 12, 4), little_endian_bytes(30.5f));
  const Points read = read_ply(path);
  ASSERT_EQ(read.size(), 3u);
  EXPECT_EQ(read[1], Vec3(1e3, 0.0, -7.0));
}

TEST_F(FileTest, PlyIntensityCountMustMatchThePoints) {
  EXPECT_THROW(write_ply(temp_path("bad.ply"), kCloud, {1.0f}), std::invalid_argument);
}

TEST_F(FileTest, PlyEmptyCloudRoundTrips) {
  const std::string path = temp_path("empty.ply");
  write_ply(path, Points{});
  EXPECT_THAT(bytes_of(path), HasSubstr("element vertex 0\n"));
  EXPECT_TRUE(read_ply(path).empty());
}

TEST_F(FileTest, PlyAsciiReadsXyzAndSkipsOtherPropertiesAndElements) {
  const std::string path = file_with("ascii.ply",
                                     "ply\n"
                                     "format ascii 1.0\n"
                                     "comment from some other tool\n"
                                     "element vertex 2\n"
                                     "property double x\n"
                                     "property uchar red\n"
                                     "property double y\n"
                                     "property float z\n"
                                     "element face 1\n"
                                     "property list uchar int vertex_indices\n"
                                     "end_header\n"
                                     "1.5 255 -2 3e-1\n"
                                     "\n"
                                     "4 0 5 6\n"
                                     "3 0 1 1\n");
  const Points points = read_ply(path);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0], Vec3(1.5, -2.0, 0.3));
  EXPECT_EQ(points[1], Vec3(4.0, 5.0, 6.0));
}

TEST_F(FileTest, PlyBinaryReadsDoublesAndSkipsOtherPropertiesAndEarlierElements) {
  std::string bytes =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "element camera 1\n"
      "property list uchar float view\n"
      "element vertex 2\n"
      "property uchar flags\n"
      "property double x\n"
      "property double y\n"
      "property double z\n"
      "end_header\n";
  bytes += std::string("\x02", 1) + little_endian_bytes(1.0f) + little_endian_bytes(2.0f);
  for (double value : {0.0, 1.25, -2.5, 3.75}) {  // flags, then x y z of vertex 0
    bytes += value == 0.0 ? std::string("\x07", 1) : little_endian_bytes(value);
  }
  bytes += std::string("\x00", 1) + little_endian_bytes(1e-3) + little_endian_bytes(2e6) +
           little_endian_bytes(-0.5);
  const Points points = read_ply(file_with("doubles.ply", bytes));
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0], Vec3(1.25, -2.5, 3.75));
  EXPECT_EQ(points[1], Vec3(1e-3, 2e6, -0.5));
}

TEST_F(FileTest, PlyTruncatedBinaryBodyIsAnError) {
  const std::string path = temp_path("truncated.ply");
  write_ply(path, kCloud);
  std::string bytes = bytes_of(path);
  bytes.resize(bytes.size() - 1);
  const std::string truncated = file_with("truncated_copy.ply", bytes);
  EXPECT_EQ(file_error_of([&] { read_ply(truncated); }),
            truncated + ": file ends inside vertex 2 of 3 declared");
}

TEST_F(FileTest, PlyBadHeadersNameTheLine) {
  const std::string not_ply = file_with("not_ply.ply", "PLY\nformat ascii 1.0\nend_header\n");
  EXPECT_THAT(file_error_of([&] { read_ply(not_ply); }),
              StartsWith(not_ply + ":1: not a PLY file"));

  const std::string big_endian =
      file_with("big_endian.ply", "ply\nformat binary_big_endian 1.0\nend_header\n");
  EXPECT_THAT(file_error_of([&] { read_ply(big_endian); }),
              StartsWith(big_endian + ":2: unsupported format 'binary_big_endian'"));

  const std::string bad_type =
      file_with("bad_type.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty real y\n");
  EXPECT_THAT(file_error_of([&] { read_ply(bad_type); }),
              StartsWith(bad_type + ":5: unknown property type 'real'"));

  const std::string no_end = file_with("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 0\n");
  EXPECT_EQ(file_error_of([&] { read_ply(no_end); }),
            no_end + ": header ends without 'end_header'");
}

TEST_F(FileTest, PlyVertexWithoutFloatXyzIsAnError) {
  const std::string no_z = file_with("no_z.ply",
                                     "ply\nformat ascii 1.0\nelement vertex 1\nproperty float "
                                     "x\nproperty float y\nend_header\n1 2\n");
  EXPECT_EQ(file_error_of([&] { read_ply(no_z); }), no_z + ": vertex element has no property 'z'");

  const std::string int_x = file_with("int_x.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\n"
                                      "property float y\nproperty float z\nend_header\n1 2 3\n");
  EXPECT_EQ(file_error_of([&] { read_ply(int_x); }),
            int_x + ": vertex property 'x' must be float or double");
}

TEST_F(FileTest, PlyAsciiBadRecordsNameTheLine) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  const std::string short_record = file_with("short.ply", header + "1 2 3\n4 5\n");
  EXPECT_EQ(file_error_of([&] { read_ply(short_record); }),
            short_record + ":9: vertex 1 has 2 values, the header declares 3");
  const std::string text = file_with("text.ply", header + "1 2 x\n");
  EXPECT_EQ(file_error_of([&] { read_ply(text); }), text + ":8: 'x' is not a number in vertex 0");
  const std::string missing = file_with("missing.ply", header + "1 2 3\n");
  EXPECT_THAT(file_error_of([&] { read_ply(missing); }),
              StartsWith(missing + ":8: file ends before vertex 1 of 2 declared"));
}

TEST_F(FileTest, PlyMissingFileNamesPathAndReason) {
  const std::string path = temp_path("does_not_exist.ply");
  EXPECT_EQ(file_error_of([&] { read_ply(path); }),
            path + ": cannot open: No such file or directory");
}

}  // namespace
}  // namespace uavslam::io
