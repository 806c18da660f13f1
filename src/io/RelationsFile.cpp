#include "io/RelationsFile.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string_view>

#include "io/OutputFile.hpp"
#include "io/TextFields.hpp"

namespace uavslam::io {
namespace {

// The N numbers of one line, named by `names` (e.g. "t1 t2 x y z roll pitch yaw") in messages.
template <std::size_t N>
std::array<double, N> numbers_of(const std::string& path, std::size_t line_number,
                                 std::string_view line, const std::string& names) {
  const std::vector<std::string_view> fields = split_fields(without_comment(line));
  if (fields.size() != N) {
    throw line_error(path, line_number,
                     "expected " + std::to_string(N) + " numbers '" + names + "', got " +
                         std::to_string(fields.size()) + ": " + quoted(line));
  }
  std::array<double, N> values{};
  for (std::size_t i = 0; i < N; ++i) {
    if (!parse_number(fields[i], values[i])) {
      throw line_error(path, line_number,
                       quoted(fields[i]) + " is not a finite number (field " +
                           std::to_string(i + 1) + ") in " + quoted(line));
    }
  }
  return values;
}

// Calls parse(line_number, line) on every line that is not blank or a comment.
template <typename ParseLine>
void for_each_data_line(const std::string& path, ParseLine parse) {
  errno = 0;
  std::ifstream file(path);
  if (!file) {
    const char* reason = errno != 0 ? std::strerror(errno) : "unknown error";
    throw file_error(path, std::string("cannot open: ") + reason);
  }
  std::string line;
  for (std::size_t line_number = 1; std::getline(file, line); ++line_number) {
    if (split_fields(without_comment(line)).empty()) continue;
    parse(line_number, line);
  }
  if (file.bad()) throw file_error(path, "read error");
}

}  // namespace

std::vector<eval::Relation> read_relations(const std::string& path) {
  std::vector<eval::Relation> relations;
  for_each_data_line(path, [&](std::size_t line_number, const std::string& line) {
    const auto v = numbers_of<8>(path, line_number, line, "t1 t2 x y z roll pitch yaw");
    relations.push_back({v[0], v[1], v[2], v[3], v[7]});
  });
  return relations;
}

std::vector<eval::PlanarStamped> read_planar_estimate(const std::string& path) {
  std::vector<eval::PlanarStamped> poses;
  for_each_data_line(path, [&](std::size_t line_number, const std::string& line) {
    const auto v = numbers_of<4>(path, line_number, line, "timestamp x y theta");
    poses.push_back({v[0], v[1], v[2], v[3]});
  });
  return poses;
}

void write_relations(const std::string& path, const std::vector<eval::Relation>& relations) {
  OutputFile file(path, "w");
  for (const eval::Relation& r : relations) {
    std::fprintf(file.stream(), "%.6f %.6f %.6f %.6f 0.000000 0.000000 0.000000 %.6f\n", r.t1, r.t2,
                 r.x, r.y, r.yaw);
  }
  file.close();
}

void write_planar_estimate(const std::string& path, const std::vector<eval::PlanarStamped>& poses) {
  OutputFile file(path, "w");
  for (const eval::PlanarStamped& p : poses) {
    std::fprintf(file.stream(), "%.6f %.6f %.6f %.6f\n", p.t, p.x, p.y, p.theta);
  }
  file.close();
}

}  // namespace uavslam::io
