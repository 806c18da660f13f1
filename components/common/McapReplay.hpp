// The loop of a sensor process replaying an MCAP recording (--source mcap:FILE): the messages of
// its channels in file order, each due at its log_time on the pacer's clock, `--rate` times
// faster than recorded. The timeline's origin is the file's first message on any channel, so the
// lidar_driver and the imu_bridge replaying one file with one --start-at publish each message at
// the moment the other's of the same log_time goes out. As with a CARMEN log, every message is
// published, late or not (the late ones counted); undecodable messages are reported on stderr as
// they are met and counted; a damaged file ends the replay at its damage (the caller reports it).
#pragma once

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <variant>

#include "common/CarmenReplay.hpp"
#include "common/RealTimePacer.hpp"
#include "common/SimSourceOptions.hpp"
#include "dds/RecordedMessageStream.hpp"

namespace uavslam::process {

// The channels of a recording that carry `base` (e.g. "scan") for a process of `vehicle`: the bare
// name, and "vehicle/base" when a vehicle is given.
std::set<std::string> recorded_topics(const std::string& vehicle, const std::string& base);

// Prints the stream's new problems: "process: skipped path: reason".
void print_new_problems(dds::RecordedMessageStream& stream, const char* process);

// Prints how the replay ended: the damage of a cut file (what was before it was published), or
// that the file had none of the wanted channels. False in that last case (nothing to replay).
bool report_replay_end(const dds::RecordedMessageStream& stream, const ReplayCounts& counts,
                       const std::string& wanted, const char* process);

// publish(const dds::RecordedMessage&): true when written. With options.max_scans, the replay
// ends before the log's (max_scans + 1)-th LaserScan message among the stream's channels.
template <typename Publish>
ReplayCounts replay_recorded(const SimSourceOptions& options, dds::RecordedMessageStream& stream,
                             const char* process, Publish publish) {
  ReplayCounts counts;
  RealTimePacer pacer = make_replay_pacer(options, 0.0, 0.0);
  std::size_t scans = 0;
  for (std::optional<dds::RecordedMessage> message = stream.next(); message;
       message = stream.next()) {
    print_new_problems(stream, process);
    const double stamp =
        (static_cast<double>(message->log_time) - static_cast<double>(stream.first_log_time())) *
        1e-9;
    if (!within_duration(options, 0.0, stamp)) break;
    if (std::holds_alternative<msg::LaserScan>(message->sample) && options.max_scans > 0 &&
        ++scans > options.max_scans) {
      break;
    }
    const RealTimePacer::Turn turn = pacer.wait_for_turn(stamp);
    if (turn == RealTimePacer::Turn::Stopped) break;
    counts.late += turn == RealTimePacer::Turn::Missed ? 1 : 0;
    counts.published += publish(*message) ? 1 : 0;
  }
  print_new_problems(stream, process);
  return counts;
}

}  // namespace uavslam::process
