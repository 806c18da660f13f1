#include "io/TumFile.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string_view>

#include "io/OutputFile.hpp"
#include "io/TextFields.hpp"

namespace uavslam::io {
namespace {

constexpr const char* kFieldNames[8] = {"t", "x", "y", "z", "qx", "qy", "qz", "qw"};

Pose parse_pose_line(const std::string& path, std::size_t line_number, std::string_view line) {
  const std::vector<std::string_view> fields = split_fields(without_comment(line));
  if (fields.size() != 8) {
    throw line_error(path, line_number,
                     "expected 8 numbers 't x y z qx qy qz qw', got " +
                         std::to_string(fields.size()) + ": " + quoted(line));
  }
  double values[8];
  for (std::size_t i = 0; i < 8; ++i) {
    if (!parse_number(fields[i], values[i])) {
      throw line_error(path, line_number,
                       quoted(fields[i]) + " is not a finite number (field " + kFieldNames[i] +
                           ") in " + quoted(line));
    }
  }
  Pose pose;
  pose.stamp = values[0];
  pose.position = Vec3(values[1], values[2], values[3]);
  // Eigen's constructor order is (w, x, y, z); the file's is qx qy qz qw.
  pose.orientation = Eigen::Quaterniond(values[7], values[4], values[5], values[6]);
  if (pose.orientation.norm() == 0.0) {
    throw line_error(path, line_number, "zero quaternion is not a rotation: " + quoted(line));
  }
  pose.orientation.normalize();
  return pose;
}

bool is_blank(std::string_view text) {
  return split_fields(text).empty();
}

}  // namespace

void write_tum(const std::string& path, const std::vector<Pose>& poses) {
  OutputFile file(path, "w");
  std::fprintf(file.stream(), "# t x y z qx qy qz qw\n");
  for (const Pose& pose : poses) {
    const Vec3& p = pose.position;
    const Eigen::Quaterniond& q = pose.orientation;
    std::fprintf(file.stream(), "%.9f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", pose.stamp, p.x(),
                 p.y(), p.z(), q.x(), q.y(), q.z(), q.w());
  }
  file.close();
}

std::vector<Pose> read_tum(const std::string& path) {
  errno = 0;
  std::ifstream file(path);
  if (!file) {
    const char* reason = errno != 0 ? std::strerror(errno) : "unknown error";
    throw file_error(path, std::string("cannot open: ") + reason);
  }
  std::vector<Pose> poses;
  std::string line;
  for (std::size_t line_number = 1; std::getline(file, line); ++line_number) {
    if (is_blank(without_comment(line))) continue;
    poses.push_back(parse_pose_line(path, line_number, line));
  }
  if (file.bad()) throw file_error(path, "read error");
  return poses;
}

}  // namespace uavslam::io
