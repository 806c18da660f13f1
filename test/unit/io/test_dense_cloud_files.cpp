// The offline mapper's cloud files: binary PCD and PLY with x y z intensity time, read back with
// the project's readers and checked byte by byte where the format fixes the layout.
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "TempDirTest.hpp"
#include "io/OutputFile.hpp"
#include "io/PcdFile.hpp"
#include "io/PlyFile.hpp"

namespace uavslam::io {
namespace {

using DenseCloudFiles = test::TempDirTest;
using ::testing::HasSubstr;

std::vector<DensePoint> two_points() {
  return {{Vec3(1.5, -2.25, 0.125), 7.0f, 1700000000.25}, {Vec3(-3.0, 4.0, 5.5), 0.0f, 12.5}};
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST_F(DenseCloudFiles, PcdRoundTripsEveryField) {
  write_pcd(path("c.pcd"), two_points());
  const std::vector<DensePoint> back = read_pcd(path("c.pcd"));
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_TRUE(back[i].position.isApprox(two_points()[i].position));
    EXPECT_EQ(back[i].intensity, two_points()[i].intensity);
    EXPECT_EQ(back[i].time, two_points()[i].time) << "time is stored as float64";
  }
}

TEST_F(DenseCloudFiles, PcdHeaderAndRecordLayoutFollowTheFormat) {
  write_pcd(path("c.pcd"), two_points());
  const std::string bytes = contents(path("c.pcd"));
  const std::string header_end = "DATA binary\n";
  const std::size_t data = bytes.find(header_end);
  ASSERT_NE(data, std::string::npos);
  const std::string header = bytes.substr(0, data);
  EXPECT_THAT(header, HasSubstr("VERSION 0.7\nFIELDS x y z intensity time\nSIZE 4 4 4 4 8\n"
                                "TYPE F F F F F\nCOUNT 1 1 1 1 1\nWIDTH 2\nHEIGHT 1\n"));
  EXPECT_THAT(header, HasSubstr("POINTS 2\n"));
  const std::size_t body = data + header_end.size();
  ASSERT_EQ(bytes.size() - body, 2u * 24u);
  float y;
  std::memcpy(&y, bytes.data() + body + 4, 4);
  EXPECT_EQ(y, -2.25f);
  double t;
  std::memcpy(&t, bytes.data() + body + 24 + 16, 8);
  EXPECT_EQ(t, 12.5);
}

TEST_F(DenseCloudFiles, PcdReaderTakesAsciiFromOtherTools) {
  const std::string file = write("a.pcd",
                                 "# from another tool\nVERSION .7\nFIELDS x y z rgb\nSIZE 4 4 4 4\n"
                                 "TYPE F F F U\nCOUNT 1 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\n"
                                 "DATA ascii\n1 2 3 255\n4.5 5 6 0\n");
  const std::vector<DensePoint> points = read_pcd(file);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_TRUE(points[1].position.isApprox(Vec3(4.5, 5.0, 6.0)));
}

TEST_F(DenseCloudFiles, PcdReaderNamesWhatIsWrong) {
  const std::string header =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
      "WIDTH 3\nHEIGHT 1\nPOINTS 3\n";
  const std::string short_data =
      write("short.pcd", header + "DATA binary\n" + std::string(20, '\0'));
  EXPECT_THAT([&] { read_pcd(short_data); },
              ::testing::ThrowsMessage<FileError>(HasSubstr("3 points need 36")));
  const std::string compressed = write("z.pcd", header + "DATA binary_compressed\n");
  EXPECT_THAT([&] { read_pcd(compressed); },
              ::testing::ThrowsMessage<FileError>(HasSubstr("binary_compressed is not supported")));
  const std::string no_z = write("noz.pcd",
                                 "FIELDS x y\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\n"
                                 "POINTS 0\nDATA ascii\n");
  EXPECT_THAT([&] { read_pcd(no_z); },
              ::testing::ThrowsMessage<FileError>(HasSubstr("no x, y or z field")));
  const std::string sizes = write("sizes.pcd", "FIELDS x y z\nSIZE 4 4\nDATA ascii\n");
  EXPECT_THAT([&] { read_pcd(sizes); },
              ::testing::ThrowsMessage<FileError>(HasSubstr("SIZE has 2 entries for 3 FIELDS")));
}

TEST_F(DenseCloudFiles, DensePlyCarriesIntensityAndTime) {
  write_ply(path("c.ply"), two_points());
  const std::string bytes = contents(path("c.ply"));
  EXPECT_THAT(bytes, HasSubstr("element vertex 2\nproperty float x\nproperty float y\n"
                               "property float z\nproperty float intensity\n"
                               "property double time\nend_header\n"));
  const std::size_t body = bytes.find("end_header\n") + 11;
  ASSERT_EQ(bytes.size() - body, 2u * 24u);
  double t;
  std::memcpy(&t, bytes.data() + body + 16, 8);
  EXPECT_EQ(t, 1700000000.25);
  const Points back = read_ply(path("c.ply"));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_TRUE(back[1].isApprox(Vec3(-3.0, 4.0, 5.5)));
}

TEST_F(DenseCloudFiles, AnUnwritableFileIsNamedWithTheReason) {
  const std::string missing_dir = path("no/such/dir/c.pcd");
  EXPECT_THAT(
      [&] { write_pcd(missing_dir, two_points()); },
      ::testing::ThrowsMessage<FileError>(HasSubstr(missing_dir + ": cannot write: No such file")));
}

TEST_F(DenseCloudFiles, AFullDiskIsReported) {
  if (!std::ifstream("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  OutputFile file("/dev/full");
  const std::string block(1 << 16, 'x');
  EXPECT_THROW(
      {
        file.write(block);
        file.close();
      },
      FileError);
}

}  // namespace
}  // namespace uavslam::io
