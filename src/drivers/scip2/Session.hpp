// One connection's conversation with a SCIP 2.0 sensor, independent of the transport: bytes in
// (with the host time they arrived), bytes out, scans with host stamps. Start-up (C-42-03320B):
// QT (stop a stream a previous session left running), SCIP2.0 (section 2: switch from SCIP 1.1),
// VV, PP, II (section 8: version, parameters, state), TM0/TM1.../TM2 (section 8, TM: round trips
// that tie the sensor clock to the host's), then ME (distance + intensity) or, when the sensor
// refuses it, MD over all measurable steps until QT. Streaming: every scan reply (status 99) is
// decoded and stamped (SensorClock). The session fails, for the owner to reconnect, when a reply
// does not come, the sensor reports an error status, or the stream falls silent.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/scip2/ResponseReader.hpp"
#include "drivers/scip2/ScanReply.hpp"
#include "drivers/scip2/SensorClock.hpp"
#include "drivers/scip2/SensorDescription.hpp"

namespace uavslam::drivers::scip2 {

struct SessionOptions {
  bool with_intensity = true;      // ask for ME; MD when the sensor refuses
  double reply_timeout_s = 1.0;    // per start-up command
  int attempts = 3;                // per start-up command
  int round_trips = 10;            // TM1 exchanges; the shortest sets the clock offset
  double silence_timeout_s = 1.0;  // streaming: no scan for max(this, 10 scan periods) fails
};

struct TimedScan {
  ScanData data;
  double sensor_s = 0.0;    // unwrapped sensor time
  double host_stamp = 0.0;  // the same instant on the host clock (the clock of `now`)
};

struct SessionCounts {
  std::uint64_t scans = 0;          // decoded and stamped
  std::uint64_t dropped_scans = 0;  // missing from the sensor's stamps (damaged ones too)
  std::uint64_t damaged_scans = 0;  // scan replies that failed a checksum or were cut short
  std::uint64_t undecodable_scans = 0;
  std::uint64_t stale_replies = 0;  // replies to nothing we are waiting for
  std::uint64_t sensor_errors = 0;  // error statuses while streaming
};

class Session {
 public:
  enum class State { Idle, Starting, Streaming, Failed };

  explicit Session(SessionOptions options = {});

  // Begins the start-up on a fresh connection (forgets partial replies and the clock).
  void start(double now);
  void receive(std::string_view bytes, double now);
  // Time passing without bytes: reply timeouts, silence.
  void tick(double now);
  // Stops the stream and the laser (QT); the bytes come out of take_output().
  void stop();

  std::string take_output();
  std::vector<TimedScan> take_scans();
  // Lines worth a log entry (sensor identity, the stream chosen, failures), oldest first.
  std::vector<std::string> take_events();

  State state() const { return state_; }
  const std::string& failure() const { return failure_; }
  const std::optional<SensorDescription>& description() const { return description_; }
  const std::optional<ScanRequest>& request() const { return request_; }
  // The sensor's own word on its health: II STAT, or the last error status while streaming.
  const std::string& sensor_status() const { return sensor_status_; }
  const SessionCounts& counts() const { return counts_; }
  const ReaderCounts& reader_counts() const { return reader_.counts(); }
  const SensorClock& clock() const { return clock_; }

 private:
  enum class Step {
    StopStream,
    Switch,
    Version,
    Parameters,
    State,
    TimeMode,
    Time,
    TimeEnd,
    Stream
  };

  void send(Step step, const std::string& command, double now);
  void handle(const Response& response, double now);
  void handle_start_up(const Response& response, double now);
  void handle_scan(const Response& response, const ScanRequest& request, double now);
  void next_after(Step step, double now);
  void request_stream(bool with_intensity, double now);
  void fail(const std::string& why);

  SessionOptions options_;
  ResponseReader reader_;
  SensorClock clock_;
  State state_ = State::Idle;
  Step step_ = Step::StopStream;
  std::string expected_echo_;
  double sent_at_ = 0.0;
  double last_scan_at_ = 0.0;
  int attempts_left_ = 0;
  int round_trips_done_ = 0;
  std::string output_;
  std::vector<TimedScan> scans_;
  std::vector<std::string> events_;
  InfoFields version_;
  std::optional<SensorDescription> description_;
  std::optional<ScanRequest> request_;
  std::optional<double> last_sensor_s_;
  std::string sensor_status_;
  std::string failure_;
  SessionCounts counts_;
};

}  // namespace uavslam::drivers::scip2
