// The loop of a sensor process replaying an MCAP recording (--source mcap:FILE): the messages of
// its channels in file order, each due at its log_time on the pacer's clock, `--rate` times
// faster than recorded. The timeline's origin is the file's first message on any channel, so the
// lidar_driver and the imu_bridge replaying one file with one --start-at publish each message at
// the moment the other's of the same log_time goes out. As with a CARMEN log, every message is
// published, late or not (the late ones counted); undecodable messages are reported on stderr as
// they are met and counted; a damaged file ends the replay at its damage (the caller reports it).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <variant>

#include <iostream>

#include "common/CarmenReplay.hpp"
#include "common/IncompatibleQos.hpp"
#include "common/PacedStream.hpp"
#include "common/ReaderGrace.hpp"
#include "common/RealTimePacer.hpp"
#include "common/SimSourceOptions.hpp"
#include "common/StopRequest.hpp"
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

// A sensor process's whole replay of a recording: waits for the subscribers, publishes every
// `Msg` of the stream's channels with `writer` (and hands any other message to `also`, when
// given: a second channel the process publishes), says what it published (`what`: e.g. "scans")
// and how the replay ended. The process's exit code: 0, or 1 when no subscriber came, the
// recording had no `channel` or a peer's QoS was incompatible.
template <typename Msg, typename Writer>
int replay_recording(const SimSourceOptions& options, dds::RecordedMessageStream& stream,
                     Writer& writer, const std::string& channel, const std::string& what,
                     const char* process,
                     const std::function<bool(const dds::RecordedMessage&)>& also = {}) {
  if (!wait_for_subscribers(writer, options.wait_for_subscribers, process)) return 1;
  QosWatch qos(process);
  const ReplayCounts counts =
      replay_recorded(options, stream, process, [&](const dds::RecordedMessage& message) {
        const auto* sample = std::get_if<Msg>(&message.sample);
        if (!sample) return also ? also(message) : false;
        qos.output(writer);
        return writer.write(*sample);
      });
  std::cerr << process << ": published " << counts.published << " " << what << " of "
            << stream.path() << ", " << stream.malformed() << " malformed and " << stream.skipped()
            << " foreign messages skipped, " << counts.late << " published late (> 0.25 s)"
            << (stop_requested() ? " (stopped)" : "") << "\n";
  const bool replayed = report_replay_end(stream, counts, channel, process);
  give_readers_the_last_samples();
  return replayed ? qos.exit_code() : 1;
}

}  // namespace uavslam::process
