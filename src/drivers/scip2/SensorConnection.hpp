// A SCIP 2.0 sensor at an address that may come and go: connects, runs a Session over the link,
// and when the link closes (unplugged, peer gone) or the session fails (no reply, error status,
// silence) drops the link and connects again after a back-off that doubles from 0.1 s to 2 s and
// resets once scans flow again. The process never has to restart.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drivers/scip2/ByteLink.hpp"
#include "drivers/scip2/Session.hpp"

namespace uavslam::drivers::scip2 {

struct SensorAddress {
  bool tcp = false;
  std::string path;  // serial
  std::string host;  // tcp
  int port = 0;      // tcp

  std::string text() const;
};

// "scip2:/dev/ttyACM0" or "scip2tcp:HOST:PORT"; nullopt for other sources, and with `problem`
// set when it is one of these but malformed.
std::optional<SensorAddress> parse_sensor_address(const std::string& source, std::string& problem);

struct ConnectionCounts {
  std::uint64_t connects = 0;    // links opened
  std::uint64_t reconnects = 0;  // links lost or sessions failed, then reopened
};

class SensorConnection {
 public:
  SensorConnection(SensorAddress address, SessionOptions options);
  ~SensorConnection();
  SensorConnection(const SensorConnection&) = delete;
  SensorConnection& operator=(const SensorConnection&) = delete;

  // Connects when due, then waits up to `wait_ms` for bytes and hands them to the session.
  void poll(int wait_ms);
  // Stops the sensor's stream (QT) if connected.
  void shut_down();

  std::vector<TimedScan> take_scans() { return session_.take_scans(); }
  std::vector<std::string> take_events();

  bool connected() const { return link_ != nullptr; }
  const Session& session() const { return session_; }
  const ConnectionCounts& counts() const { return counts_; }
  // The sum over every session so far (each reconnect starts a new one).
  SessionCounts total_session_counts() const;
  ReaderCounts total_reader_counts() const;

 private:
  void connect(double now);
  void drop(const std::string& why, double now);
  void flush_output();

  SensorAddress address_;
  SessionOptions options_;
  Session session_;
  std::unique_ptr<ByteLink> link_;
  double next_attempt_ = 0.0;
  double backoff_ = 0.1;
  bool ever_connected_ = false;
  std::string last_error_;
  std::vector<std::string> events_;
  SessionCounts past_session_counts_;
  ReaderCounts past_reader_counts_;
  ConnectionCounts counts_;
};

// Seconds since the epoch on the system clock: the clock scans are stamped on.
double host_now();

}  // namespace uavslam::drivers::scip2
