// Progress of a long pass on stderr. On a terminal: one line redrawn in place with a bar, the
// rate and the time left; otherwise (a log file, CI) a plain line every 10 % so the log shows the
// work moving without filling up with carriage returns.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>

namespace uavslam::cli {

class ProgressBar {
 public:
  // total 0: unknown (no percentage or time left, only the count and the rate).
  ProgressBar(std::string label, std::size_t total, std::string unit, std::ostream& out,
              bool terminal);

  // Called often (every item); draws at most every 0.2 s on a terminal.
  void update(std::size_t done);
  // The final line, whatever the throttle.
  void finish(std::size_t done);

 private:
  void draw(std::size_t done, bool final_line);
  std::string line(std::size_t done) const;

  using Clock = std::chrono::steady_clock;
  std::string label_;
  std::size_t total_;
  std::string unit_;
  std::ostream& out_;
  bool terminal_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_draw_{};
  std::size_t next_plain_line_ = 0;  // the done count of the next 10 % step
  std::size_t last_drawn_ = SIZE_MAX;
};

}  // namespace uavslam::cli
