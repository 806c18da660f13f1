// libFuzzer target: the CARMEN log reader (src/io/CarmenLog) and the conversion of what it reads
// to the core's scans. Any input must give messages or counted malformed lines, never a crash,
// undefined behaviour or an unbounded allocation.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <variant>

#include "FuzzInputFile.hpp"
#include "io/CarmenLog.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static uavslam::fuzz::FuzzInputFile file;
  uavslam::io::CarmenLogReader reader(file.hold(data, size));
  while (std::optional<uavslam::io::CarmenMessage> message = reader.next()) {
    if (const auto* scan = std::get_if<uavslam::io::CarmenScan>(&*message)) {
      auto geometry =
          std::make_shared<const uavslam::ScanGeometry>(uavslam::io::to_scan_geometry(*scan));
      const uavslam::Scan core = uavslam::io::to_core_scan(*scan, geometry, 0);
      if (core.ranges.size() != geometry->directions.size()) __builtin_trap();
    }
  }
  return 0;
}
