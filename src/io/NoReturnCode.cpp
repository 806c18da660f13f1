#include "io/NoReturnCode.hpp"

#include <cmath>
#include <fstream>
#include <string_view>

#include "io/TextFields.hpp"

namespace uavslam::io {

void RangeTally::add(float range) {
  if (std::isfinite(range) && range > 0.0f) ++counts_[range];
}

std::optional<NoReturnCode> RangeTally::no_return_code() const {
  if (counts_.empty()) return std::nullopt;
  const auto& [largest, readings] = *counts_.rbegin();
  if (readings < kMinReadings) return std::nullopt;
  const auto band_start = counts_.lower_bound(static_cast<float>(largest * (1.0 - kBand)));
  for (auto it = band_start; it->first < largest; ++it) {
    if (static_cast<double>(readings) < kMinRatio * static_cast<double>(it->second)) {
      return std::nullopt;
    }
  }
  return NoReturnCode{largest, readings};
}

std::optional<NoReturnCode> learn_flaser_no_return_code(const std::string& path) {
  std::ifstream in(path);
  RangeTally tally;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("FLASER ", 0) != 0) continue;
    const std::vector<std::string_view> fields = split_fields(line);
    std::size_t beams = 0;
    // beams > size - 2, not size < beams + 2: a count near SIZE_MAX would wrap the sum.
    if (fields.size() < 2 || !parse_number(fields[1], beams) || beams > fields.size() - 2) continue;
    for (std::size_t i = 0; i < beams; ++i) {
      float range = 0.0f;
      if (parse_number(fields[2 + i], range)) tally.add(range);
    }
  }
  return tally.no_return_code();
}

}  // namespace uavslam::io
