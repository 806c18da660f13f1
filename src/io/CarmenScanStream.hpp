// The laser scans of a CARMEN log, streamed in file order with their timeline stamps
// (CarmenTimeline.hpp), for replaying a log message by message however large it is. ODOM
// messages are passed over; malformed lines are counted by the reader and their descriptions
// handed out as they are met, so a replay can report them while it runs.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/CarmenLog.hpp"
#include "io/CarmenTimeline.hpp"

namespace uavslam::io {

struct TimedCarmenScan {
  CarmenScan scan;
  double stamp = 0.0;     // on the timeline: strictly increasing in file order
  std::size_t index = 0;  // 0-based among the log's scans
};

class CarmenScanStream {
 public:
  // max_scans: stop after this many scans; 0 = all. Throws FileError naming the path when it
  // cannot be opened.
  explicit CarmenScanStream(const std::string& path, std::size_t max_scans = 0);

  // The next FLASER/ROBOTLASER1 scan; nullopt at the end of the file or after max_scans.
  std::optional<TimedCarmenScan> next();

  // The descriptions ("path:line: reason") of the malformed lines met since the last call; the
  // reader keeps the first kMaxReportedProblems, malformed_lines() counts them all.
  std::vector<std::string> take_new_problems();

  std::size_t scans() const { return scans_; }
  std::size_t malformed_lines() const { return reader_.malformed_lines(); }
  const CarmenTimeline& timeline() const { return timeline_; }
  const std::optional<NoReturnCode>& flaser_no_return() const { return reader_.flaser_no_return(); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  CarmenLogReader reader_;
  CarmenTimeline timeline_;
  std::size_t max_scans_;
  std::size_t scans_ = 0;
  std::size_t problems_taken_ = 0;
};

}  // namespace uavslam::io
