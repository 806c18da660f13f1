#include "drivers/scip2/Session.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "drivers/scip2/Encoding.hpp"

namespace uavslam::drivers::scip2 {
namespace {

// Section 7: "00" command accepted, "99" a scan reply of a streaming command. Section 8, TM:
// "02"/"03" mean already in / not in time-adjust mode, harmless.
constexpr const char* kOk = "00";
constexpr const char* kScanData = "99";

bool is_ok(const Response& r) {
  return r.status == kOk;
}

}  // namespace

Session::Session(SessionOptions options) : options_(options) {}

void Session::start(double now) {
  reader_.reset();
  clock_.reset();
  output_.clear();
  failure_.clear();
  description_.reset();
  request_.reset();
  last_sensor_s_.reset();
  round_trips_done_ = 0;
  state_ = State::Starting;
  send(Step::StopStream, "QT", now);
}

void Session::stop() {
  output_ += "QT\n";
  state_ = State::Idle;
}

std::string Session::take_output() {
  return std::exchange(output_, {});
}

std::vector<TimedScan> Session::take_scans() {
  return std::exchange(scans_, {});
}

std::vector<std::string> Session::take_events() {
  return std::exchange(events_, {});
}

void Session::send(Step step, const std::string& command, double now) {
  if (step != step_) attempts_left_ = options_.attempts;
  step_ = step;
  expected_echo_ = command;
  output_ += command + "\n";
  sent_at_ = now;
}

void Session::fail(const std::string& why) {
  state_ = State::Failed;
  failure_ = why;
  events_.push_back("failed: " + why);
}

void Session::receive(std::string_view bytes, double now) {
  std::vector<Response> responses;
  reader_.feed(bytes, responses);
  for (const Response& r : responses) {
    if (state_ == State::Failed || state_ == State::Idle) break;
    handle(r, now);
  }
}

void Session::tick(double now) {
  if (state_ == State::Starting && now - sent_at_ > options_.reply_timeout_s) {
    if (step_ == Step::StopStream || step_ == Step::Switch) {
      next_after(step_, now);  // an idle SCIP 2.0 sensor may say nothing useful to either
    } else if (--attempts_left_ > 0) {
      send(step_, expected_echo_, now);
    } else {
      fail("no reply to " + expected_echo_ + " within " + std::to_string(options_.reply_timeout_s) +
           " s");
    }
    return;
  }
  if (state_ == State::Streaming && description_) {
    const double limit = std::max(options_.silence_timeout_s, 10.0 * description_->scan_period());
    if (now - last_scan_at_ > limit) {
      std::ostringstream why;
      why << "no scan for " << now - last_scan_at_ << " s";
      fail(why.str());
    }
  }
}

void Session::handle(const Response& response, double now) {
  if (state_ == State::Streaming && request_) {
    const auto scan_request = parse_scan_echo(response.echo);
    if (scan_request && scan_request->continuous &&
        response.echo.compare(0, 12, command_text(*request_), 0, 12) == 0) {
      handle_scan(response, *scan_request, now);
      return;
    }
  }
  if (state_ == State::Starting) {
    handle_start_up(response, now);
    return;
  }
  ++counts_.stale_replies;
}

void Session::handle_start_up(const Response& response, double now) {
  const bool is_stream_ack =
      step_ == Step::Stream && response.echo.compare(0, 12, expected_echo_, 0, 12) == 0;
  if (response.echo != expected_echo_ && !is_stream_ack) {
    ++counts_.stale_replies;  // e.g. scans of a stream the sensor was still sending
    return;
  }
  if (!response.intact) {
    send(step_, expected_echo_, now);  // damaged: ask again
    return;
  }
  switch (step_) {
    case Step::StopStream:
    case Step::Switch:
    case Step::TimeMode:
    case Step::TimeEnd:
      break;
    case Step::Version:
      if (!is_ok(response)) return fail("VV refused with status " + response.status);
      version_ = parse_info_lines(response.data);
      break;
    case Step::Parameters: {
      if (!is_ok(response)) return fail("PP refused with status " + response.status);
      std::string problem;
      description_ = describe_sensor(parse_info_lines(response.data), version_, problem);
      if (!description_) return fail(problem);
      std::ostringstream line;
      line << "sensor " << description_->model << " serial '" << description_->serial
           << "' firmware '" << description_->firmware << "': " << description_->beams()
           << " steps " << description_->first_step << ".." << description_->last_step
           << ", front step " << description_->front_step << ", "
           << 360.0 / description_->steps_per_turn << " deg/step, "
           << 1.0 / description_->scan_period() << " Hz, " << description_->min_distance_mm << ".."
           << description_->max_distance_mm << " mm";
      events_.push_back(line.str());
      break;
    }
    case Step::State: {
      const InfoFields state = parse_info_lines(response.data);
      const auto stat = state.find("STAT");
      sensor_status_ = stat == state.end() ? "unknown" : stat->second;
      events_.push_back("sensor state: " + sensor_status_);
      break;
    }
    case Step::Time:
      if (is_ok(response) && !response.data.empty()) {
        if (const auto stamp = decode(response.data.front())) {
          clock_.add_round_trip(sent_at_, *stamp, now);
        }
      }
      break;
    case Step::Stream:
      if (!is_ok(response)) {
        if (request_ && request_->with_intensity) {
          events_.push_back("ME refused with status " + response.status + ": using MD");
          request_stream(false, now);
          return;
        }
        return fail(expected_echo_ + " refused with status " + response.status);
      }
      break;
  }
  next_after(step_, now);
}

void Session::next_after(Step step, double now) {
  switch (step) {
    case Step::StopStream:
      return send(Step::Switch, "SCIP2.0", now);
    case Step::Switch:
      return send(Step::Version, "VV", now);
    case Step::Version:
      return send(Step::Parameters, "PP", now);
    case Step::Parameters:
      return send(Step::State, "II", now);
    case Step::State:
      return send(Step::TimeMode, "TM0", now);
    case Step::TimeMode:
      return send(Step::Time, "TM1", now);
    case Step::Time:
      if (++round_trips_done_ < options_.round_trips) return send(Step::Time, "TM1", now);
      return send(Step::TimeEnd, "TM2", now);
    case Step::TimeEnd:
      if (clock_.round_trip_seen()) {
        std::ostringstream line;
        line << "clock: best TM round trip " << clock_.best_round_trip_s() * 1e3 << " ms";
        events_.push_back(line.str());
      } else {
        events_.push_back("clock: no TM round trip (stamps will lag by the sensor's latency)");
      }
      return request_stream(options_.with_intensity, now);
    case Step::Stream:
      state_ = State::Streaming;
      last_scan_at_ = now;
      events_.push_back("streaming " + expected_echo_);
      return;
  }
}

void Session::request_stream(bool with_intensity, double now) {
  ScanRequest r;
  r.with_intensity = with_intensity;
  r.continuous = true;
  r.first_step = description_->first_step;
  r.last_step = description_->last_step;
  request_ = r;
  send(Step::Stream, command_text(r), now);
}

void Session::handle_scan(const Response& response, const ScanRequest& request, double now) {
  if (response.status != kScanData) {
    if (response.status == kOk) return;  // the acknowledgement of our own request, again
    ++counts_.sensor_errors;
    sensor_status_ = "error status " + response.status;
    return fail("sensor reported status " + response.status + " while streaming");
  }
  if (!response.intact) {
    ++counts_.damaged_scans;
    return;
  }
  std::string problem;
  auto data = decode_scan(response, request, problem);
  if (!data) {
    ++counts_.undecodable_scans;
    return;
  }
  last_scan_at_ = now;
  TimedScan scan;
  scan.sensor_s = clock_.add_arrival(data->timestamp_ms, now);
  if (last_sensor_s_) {
    const double gap = (scan.sensor_s - *last_sensor_s_) / description_->scan_period();
    if (gap > 1.5) counts_.dropped_scans += static_cast<std::uint64_t>(std::lround(gap)) - 1;
  }
  last_sensor_s_ = scan.sensor_s;
  scan.host_stamp = clock_.to_host(scan.sensor_s).value_or(now);
  scan.data = std::move(*data);
  ++counts_.scans;
  scans_.push_back(std::move(scan));
}

}  // namespace uavslam::drivers::scip2
