// The measurement commands and their replies (C-42-03320B section 8, "MD-MS Command" and
// "GD-GS Command"; ME/GE are the UTM-30LX's distance + intensity variants with the same layout):
// MD/ME<start:4><end:4><cluster:2><interval:1><scans:2> streams scans, GD/GE<start:4><end:4>
// <cluster:2> asks for one. Each scan reply's data is a 4-character time stamp (ms, 24 bits)
// then the steps' values in 3-character encoding (ME/GE: distance then intensity per step),
// split into lines of at most 64 characters; a value may straddle two lines.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "drivers/scip2/ResponseReader.hpp"

namespace uavslam::drivers::scip2 {

struct ScanRequest {
  bool with_intensity = false;  // ME/GE instead of MD/GD
  bool continuous = true;       // MD/ME instead of GD/GE
  int first_step = 0;
  int last_step = 0;
  int cluster = 1;   // steps merged into one value (their minimum distance)
  int interval = 0;  // MD/ME: scans skipped between two sent
  int scans = 0;     // MD/ME: 0 = until QT

  int values() const { return (last_step - first_step + cluster) / cluster; }
};

// The command line (without LF) for `request`.
std::string command_text(const ScanRequest& request);
// The request an echo line names (MD, ME, GD, GE), or nullopt for any other line.
std::optional<ScanRequest> parse_scan_echo(const std::string& echo);

struct ScanData {
  std::uint32_t timestamp_ms = 0;  // the sensor's clock, 24 bits, wraps every 4.66 h
  std::vector<std::uint32_t> distances_mm;
  std::vector<std::uint32_t> intensities;  // empty for MD/GD
};

// The scan in a reply to `request`, or nullopt with `problem` set (too few or too many values, a
// character that is not an encoded value, no time stamp).
std::optional<ScanData> decode_scan(const Response& response, const ScanRequest& request,
                                    std::string& problem);

// The data lines of a scan reply for `scan` (time stamp line, then 64-character blocks), each
// with its checksum, as a sensor sends them: what the emulator and the tests build.
std::vector<std::string> encode_scan_lines(const ScanData& scan);

}  // namespace uavslam::drivers::scip2
