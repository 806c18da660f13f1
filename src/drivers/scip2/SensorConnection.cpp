#include "drivers/scip2/SensorConnection.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>
#include <utility>

namespace uavslam::drivers::scip2 {
namespace {

constexpr const char* kSerialPrefix = "scip2:";
constexpr const char* kTcpPrefix = "scip2tcp:";
constexpr double kFirstBackoff = 0.1;
constexpr double kLongestBackoff = 2.0;
constexpr int kConnectTimeoutMs = 1000;

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

SessionCounts add(SessionCounts a, const SessionCounts& b) {
  a.scans += b.scans;
  a.dropped_scans += b.dropped_scans;
  a.damaged_scans += b.damaged_scans;
  a.undecodable_scans += b.undecodable_scans;
  a.stale_replies += b.stale_replies;
  a.sensor_errors += b.sensor_errors;
  return a;
}

ReaderCounts add(ReaderCounts a, const ReaderCounts& b) {
  a.responses += b.responses;
  a.garbage_bytes += b.garbage_bytes;
  a.checksum_errors += b.checksum_errors;
  a.cut_short += b.cut_short;
  return a;
}

}  // namespace

std::string SensorAddress::text() const {
  return tcp ? host + ":" + std::to_string(port) : path;
}

std::optional<SensorAddress> parse_sensor_address(const std::string& source, std::string& problem) {
  SensorAddress address;
  if (starts_with(source, kTcpPrefix)) {
    const std::string rest = source.substr(std::string(kTcpPrefix).size());
    const auto colon = rest.rfind(':');
    char* end = nullptr;
    const long port =
        colon == std::string::npos ? 0 : std::strtol(rest.c_str() + colon + 1, &end, 10);
    if (colon == std::string::npos || colon == 0 || *end != '\0' || port <= 0 || port > 65535) {
      problem = "expected scip2tcp:HOST:PORT, got '" + source + "'";
      return std::nullopt;
    }
    address.tcp = true;
    address.host = rest.substr(0, colon);
    address.port = static_cast<int>(port);
    return address;
  }
  if (starts_with(source, kSerialPrefix)) {
    address.path = source.substr(std::string(kSerialPrefix).size());
    if (address.path.empty()) {
      problem = "expected scip2:DEVICE (e.g. scip2:/dev/ttyACM0), got '" + source + "'";
      return std::nullopt;
    }
    return address;
  }
  return std::nullopt;
}

double host_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

SensorConnection::SensorConnection(SensorAddress address, SessionOptions options)
    : address_(std::move(address)), options_(options), session_(options) {}

SensorConnection::~SensorConnection() {
  shut_down();
}

std::vector<std::string> SensorConnection::take_events() {
  for (std::string& e : session_.take_events()) events_.push_back(std::move(e));
  return std::exchange(events_, {});
}

SessionCounts SensorConnection::total_session_counts() const {
  return add(past_session_counts_, session_.counts());
}

ReaderCounts SensorConnection::total_reader_counts() const {
  return add(past_reader_counts_, session_.reader_counts());
}

void SensorConnection::shut_down() {
  if (!link_) return;
  session_.stop();
  flush_output();
  link_.reset();
}

void SensorConnection::poll(int wait_ms) {
  if (!link_) {
    const double now = host_now();
    if (now >= next_attempt_) connect(now);
    if (!link_) {
      std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
      return;
    }
  }
  std::string bytes;
  const ByteLink::Read read = link_->read(bytes, wait_ms);
  const double now = host_now();
  if (read == ByteLink::Read::Closed) return drop("the device closed the link", now);
  if (read == ByteLink::Read::Data) session_.receive(bytes, now);
  session_.tick(now);
  if (session_.state() == Session::State::Failed) return drop(session_.failure(), now);
  if (session_.state() == Session::State::Streaming && session_.counts().scans > 0) {
    backoff_ = kFirstBackoff;
  }
  flush_output();
}

void SensorConnection::connect(double now) {
  std::string error;
  link_ = address_.tcp ? open_tcp(address_.host, address_.port, kConnectTimeoutMs, error)
                       : open_serial(address_.path, error);
  if (!link_) {
    if (error != last_error_) events_.push_back(error + " (retrying)");
    last_error_ = error;
    next_attempt_ = now + backoff_;
    backoff_ = std::min(backoff_ * 2.0, kLongestBackoff);
    return;
  }
  last_error_.clear();
  ++counts_.connects;
  if (ever_connected_) ++counts_.reconnects;
  ever_connected_ = true;
  past_session_counts_ = add(past_session_counts_, session_.counts());
  past_reader_counts_ = add(past_reader_counts_, session_.reader_counts());
  session_ = Session(options_);
  events_.push_back((counts_.reconnects ? "reconnected to " : "connected to ") + address_.text());
  session_.start(host_now());
  flush_output();
}

void SensorConnection::drop(const std::string& why, double now) {
  events_.push_back("lost " + address_.text() + ": " + why);
  for (std::string& e : session_.take_events()) events_.push_back(std::move(e));
  link_.reset();
  next_attempt_ = now + backoff_;
  backoff_ = std::min(backoff_ * 2.0, kLongestBackoff);
}

void SensorConnection::flush_output() {
  const std::string out = session_.take_output();
  if (!out.empty() && link_ && !link_->write(out)) {
    link_.reset();
    events_.push_back("lost " + address_.text() + ": write failed");
  }
}

}  // namespace uavslam::drivers::scip2
