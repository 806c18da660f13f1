// The loop of a sensor process replaying a CARMEN log (--source carmen:FILE): every scan of the
// log in file order, each due at its timeline stamp (io/CarmenTimeline.hpp) on the pacer's clock,
// `--rate` times faster than recorded, from --start-at when given (the timeline of
// RealTimePacer.hpp, shared by lidar_driver and imu_bridge). Unlike the simulator's sensors, a
// replay publishes every scan, late or not: the log is the data, and a late one is counted.
// Malformed lines are reported on stderr as they are met, and counted.
#pragma once

#include <cstdint>
#include <optional>

#include "common/RealTimePacer.hpp"
#include "common/SimSourceOptions.hpp"
#include "io/CarmenScanStream.hpp"

namespace uavslam::process {

struct ReplayCounts {
  std::uint64_t published = 0;
  std::uint64_t late = 0;  // published more than a quarter second after their due time
};

// How far ahead of its scan the imu_bridge publishes the orientation sample of that scan, in s of
// wall time: the matcher needs it by the time the scan arrives (a scan with no orientation within
// imu.max_gap is dropped). 50 ms covers the transport and scheduling; at high rates it is capped
// at 0.5 s of log time, so samples never run further ahead than the ImuBuffer's 2 s history.
double orientation_lead(double rate);

// The pacer of a replay whose first scan is stamped `first_stamp`: on the shared timeline of
// --start-at, `lead` s of wall time early, when given; else from the first scan waited for.
RealTimePacer make_replay_pacer(const SimSourceOptions& options, double first_stamp, double lead);

// Prints the descriptions of the malformed lines met since the last call: "process: skipped
// path:line: reason".
void print_new_problems(io::CarmenScanStream& stream, const char* process);

// publish(const io::TimedCarmenScan&): true when written.
template <typename Publish>
ReplayCounts replay_carmen_scans(const SimSourceOptions& options, io::CarmenScanStream& stream,
                                 double lead, const char* process, Publish publish) {
  ReplayCounts counts;
  std::optional<io::TimedCarmenScan> scan = stream.next();
  print_new_problems(stream, process);
  if (!scan) return counts;
  const double first_stamp = scan->stamp;
  RealTimePacer pacer = make_replay_pacer(options, first_stamp, lead);
  while (scan && within_duration(options, first_stamp, scan->stamp)) {
    const RealTimePacer::Turn turn = pacer.wait_for_turn(scan->stamp);
    if (turn == RealTimePacer::Turn::Stopped) break;
    counts.late += turn == RealTimePacer::Turn::Missed ? 1 : 0;
    counts.published += publish(*scan) ? 1 : 0;
    scan = stream.next();
    print_new_problems(stream, process);
  }
  return counts;
}

}  // namespace uavslam::process
