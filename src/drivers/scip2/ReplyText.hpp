// Replies as a sensor writes them (C-42-03320B section 7): the echo, the status with its
// checksum, the data lines, and the empty line that ends the reply. For the emulator and tests.
#pragma once

#include <string>
#include <vector>

namespace uavslam::drivers::scip2 {

// `lines` already carry their checksums (info_line, encode_scan_lines).
std::string reply_text(const std::string& echo, const std::string& status,
                       const std::vector<std::string>& lines = {});
// A VV/PP/II line: "KEY:VALUE;" + the checksum of "KEY:VALUE" (section 8, PP example).
std::string info_line(const std::string& key, const std::string& value);

}  // namespace uavslam::drivers::scip2
