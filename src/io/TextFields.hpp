// The pieces every line-oriented text format of ours parses with (TUM trajectories, relations
// and planar estimates, CARMEN logs): whitespace-separated fields after an optional '#' comment,
// locale-independent finite numbers, and a line quoted short enough for an error message.
#pragma once

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace uavslam::io {

// The text before a '#' (numpy.loadtxt's comments="#", as evo reads TUM files).
inline std::string_view without_comment(std::string_view line) {
  return line.substr(0, line.find('#'));
}

// Fields separated by spaces, tabs or a stray '\r' (CRLF files).
std::vector<std::string_view> split_fields(std::string_view text);

// Parses the whole of `text` as a finite number (a leading '+' allowed for floating point);
// from_chars is locale independent, so "1.5" reads the same whatever the user's locale.
template <typename T>
bool parse_number(std::string_view text, T& value) {
  if constexpr (std::is_floating_point_v<T>) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  }
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || stop != end) return false;
  if constexpr (std::is_floating_point_v<T>) return std::isfinite(value);
  return true;
}

// 'text', cut to 80 characters with "..." for messages.
std::string quoted(std::string_view text);

}  // namespace uavslam::io
