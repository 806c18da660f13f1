#include "drivers/scip2/ScanReply.hpp"

#include <cstdio>

#include "drivers/scip2/Encoding.hpp"

namespace uavslam::drivers::scip2 {
namespace {

constexpr std::size_t kBlockCharacters = 64;  // section 8, MD: "Data Block (64 byte)"

bool read_decimal(const std::string& text, std::size_t at, std::size_t width, int& value) {
  if (at + width > text.size()) return false;
  value = 0;
  for (std::size_t i = at; i < at + width; ++i) {
    if (text[i] < '0' || text[i] > '9') return false;
    value = value * 10 + (text[i] - '0');
  }
  return true;
}

std::string decimal(int value, int width) {
  char text[16];
  std::snprintf(text, sizeof text, "%0*d", width, value);
  return text;
}

}  // namespace

std::string command_text(const ScanRequest& r) {
  std::string text =
      r.continuous ? (r.with_intensity ? "ME" : "MD") : (r.with_intensity ? "GE" : "GD");
  text += decimal(r.first_step, 4) + decimal(r.last_step, 4) + decimal(r.cluster, 2);
  if (r.continuous) text += decimal(r.interval, 1) + decimal(r.scans, 2);
  return text;
}

std::optional<ScanRequest> parse_scan_echo(const std::string& echo) {
  if (echo.size() < 12) return std::nullopt;
  ScanRequest r;
  const std::string command = echo.substr(0, 2);
  if (command == "MD" || command == "ME") {
    r.continuous = true;
  } else if (command == "GD" || command == "GE") {
    r.continuous = false;
  } else {
    return std::nullopt;
  }
  r.with_intensity = command[1] == 'E';
  if (!read_decimal(echo, 2, 4, r.first_step) || !read_decimal(echo, 6, 4, r.last_step) ||
      !read_decimal(echo, 10, 2, r.cluster)) {
    return std::nullopt;
  }
  if (r.continuous &&
      (!read_decimal(echo, 12, 1, r.interval) || !read_decimal(echo, 13, 2, r.scans))) {
    return std::nullopt;
  }
  if (r.cluster == 0) r.cluster = 1;  // section 8: cluster count 00 means 1
  if (r.last_step < r.first_step) return std::nullopt;
  return r;
}

std::optional<ScanData> decode_scan(const Response& response, const ScanRequest& request,
                                    std::string& problem) {
  if (response.data.empty() || response.data.front().size() != kFourCharacters) {
    problem = "no time stamp";
    return std::nullopt;
  }
  ScanData scan;
  const auto stamp = decode(response.data.front());
  if (!stamp) {
    problem = "time stamp is not encoded";
    return std::nullopt;
  }
  scan.timestamp_ms = *stamp;
  std::string values;
  for (std::size_t i = 1; i < response.data.size(); ++i) values += response.data[i];
  const std::size_t per_step = request.with_intensity ? 2 : 1;
  const std::size_t expected = static_cast<std::size_t>(request.values()) * per_step;
  if (values.size() != expected * kThreeCharacters) {
    problem = std::to_string(values.size()) + " data characters, expected " +
              std::to_string(expected * kThreeCharacters);
    return std::nullopt;
  }
  scan.distances_mm.reserve(static_cast<std::size_t>(request.values()));
  for (std::size_t i = 0; i < expected; ++i) {
    const auto value =
        decode(std::string_view(values).substr(i * kThreeCharacters, kThreeCharacters));
    if (!value) {
      problem = "value " + std::to_string(i) + " is not encoded";
      return std::nullopt;
    }
    if (per_step == 2 && i % 2 == 1) {
      scan.intensities.push_back(*value);
    } else {
      scan.distances_mm.push_back(*value);
    }
  }
  return scan;
}

std::vector<std::string> encode_scan_lines(const ScanData& scan) {
  std::string values;
  const bool with_intensity = !scan.intensities.empty();
  for (std::size_t i = 0; i < scan.distances_mm.size(); ++i) {
    values += encode(scan.distances_mm[i], kThreeCharacters);
    if (with_intensity) values += encode(scan.intensities[i], kThreeCharacters);
  }
  std::vector<std::string> lines;
  const std::string stamp = encode(scan.timestamp_ms, kFourCharacters);
  lines.push_back(stamp + checksum(stamp));
  for (std::size_t at = 0; at < values.size(); at += kBlockCharacters) {
    const std::string block = values.substr(at, kBlockCharacters);
    lines.push_back(block + checksum(block));
  }
  return lines;
}

}  // namespace uavslam::drivers::scip2
