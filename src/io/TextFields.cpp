#include "io/TextFields.hpp"

#include <algorithm>

namespace uavslam::io {

std::vector<std::string_view> split_fields(std::string_view text) {
  constexpr std::string_view kWhitespace = " \t\r\n\v\f";
  std::vector<std::string_view> fields;
  std::size_t begin = text.find_first_not_of(kWhitespace);
  while (begin != std::string_view::npos) {
    const std::size_t end = std::min(text.find_first_of(kWhitespace, begin), text.size());
    fields.push_back(text.substr(begin, end - begin));
    begin = text.find_first_not_of(kWhitespace, end);
  }
  return fields;
}

std::string quoted(std::string_view text) {
  constexpr std::size_t kShownTextLength = 80;
  if (text.size() > kShownTextLength) {
    return "'" + std::string(text.substr(0, kShownTextLength)) + "...'";
  }
  return "'" + std::string(text) + "'";
}

}  // namespace uavslam::io
