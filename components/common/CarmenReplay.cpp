#include "common/CarmenReplay.hpp"

#include <algorithm>
#include <iostream>
#include <string>

namespace uavslam::process {

double orientation_lead(double rate) {
  constexpr double kWallLead = 0.05;   // s
  constexpr double kMaxLogLead = 0.5;  // s of log time
  return std::min(kWallLead, kMaxLogLead / rate);
}

RealTimePacer make_replay_pacer(const SimSourceOptions& options, double first_stamp, double lead) {
  if (options.start_at <= 0.0) return RealTimePacer(options.rate);
  return RealTimePacer(options.rate, options.start_at - lead, first_stamp);
}

void print_new_problems(io::CarmenScanStream& stream, const char* process) {
  for (const std::string& problem : stream.take_new_problems()) {
    std::cerr << process << ": skipped " << problem << "\n";
  }
}

}  // namespace uavslam::process
