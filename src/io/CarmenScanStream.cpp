#include "io/CarmenScanStream.hpp"

#include <utility>
#include <variant>

namespace uavslam::io {

CarmenScanStream::CarmenScanStream(const std::string& path, std::size_t max_scans)
    : path_(path), reader_(path), max_scans_(max_scans) {}

std::optional<TimedCarmenScan> CarmenScanStream::next() {
  if (max_scans_ > 0 && scans_ >= max_scans_) return std::nullopt;
  while (std::optional<CarmenMessage> message = reader_.next()) {
    auto* scan = std::get_if<CarmenScan>(&*message);
    if (!scan) continue;
    TimedCarmenScan timed{std::move(*scan), 0.0, scans_++};
    timed.stamp = timeline_.next(timed.scan.ipc_timestamp);
    return timed;
  }
  return std::nullopt;
}

std::vector<std::string> CarmenScanStream::take_new_problems() {
  const std::vector<std::string>& all = reader_.problems();
  std::vector<std::string> fresh(all.begin() + static_cast<std::ptrdiff_t>(problems_taken_),
                                 all.end());
  problems_taken_ = all.size();
  return fresh;
}

}  // namespace uavslam::io
