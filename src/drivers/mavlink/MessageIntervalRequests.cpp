#include "drivers/mavlink/MessageIntervalRequests.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "drivers/mavlink/CommonMessages.hpp"

namespace uavslam::mavlink {
namespace {

std::string message_name(std::uint16_t id) {
  const MessageDefinition* known = find_definition(id);
  return known ? known->name() : "message " + std::to_string(id);
}

}  // namespace

float interval_us(double rate_hz) {
  return static_cast<float>(std::round(1e6 / rate_hz));
}

MessageIntervalRequests::MessageIntervalRequests(std::vector<StreamRequest> wanted, double timeout,
                                                 int attempts)
    : timeout_(timeout), attempts_(std::max(attempts, 1)) {
  for (const StreamRequest& stream : wanted) {
    if (stream.rate_hz > 0) requests_.emplace_back(stream);
  }
}

void MessageIntervalRequests::start(std::uint8_t target_system, std::uint8_t target_component) {
  target_system_ = target_system;
  target_component_ = target_component;
  started_ = true;
  for (Request& request : requests_) request = Request{request.stream};
}

MessageIntervalRequests::Request* MessageIntervalRequests::in_flight() {
  const auto found = std::find_if(requests_.begin(), requests_.end(),
                                  [](const Request& r) { return r.state == State::kAwaitingAck; });
  return found == requests_.end() ? nullptr : &*found;
}

void MessageIntervalRequests::tick(double now, const SendCommand& send) {
  if (!started_) return;
  if (Request* waiting = in_flight()) {
    if (now < deadline_) return;
    if (waiting->transmissions < attempts_) {
      transmit(*waiting, now, send);
      return;
    }
    give_up(*waiting);
  }
  const auto next = std::find_if(requests_.begin(), requests_.end(),
                                 [](const Request& r) { return r.state == State::kPending; });
  if (next != requests_.end()) transmit(*next, now, send);
}

void MessageIntervalRequests::transmit(Request& request, double now, const SendCommand& send) {
  CommandLong command;
  command.target_system = target_system_;
  command.target_component = target_component_;
  command.command = kMavCmdSetMessageInterval;
  command.confirmation = static_cast<std::uint8_t>(std::min(request.transmissions, 255));
  command.param1 = static_cast<float>(request.stream.message_id);
  command.param2 = interval_us(request.stream.rate_hz);
  send(command);
  ++request.transmissions;
  request.state = State::kAwaitingAck;
  deadline_ = now + timeout_;
  ++counts_.sent;
}

void MessageIntervalRequests::give_up(Request& request) {
  if (request.last_result) {
    request.state = State::kRefused;
    ++counts_.refused;
    report(request, "refused (" + mav_result_name(*request.last_result) + " to each of " +
                        std::to_string(request.transmissions) + " requests)");
    return;
  }
  request.state = State::kUnanswered;
  ++counts_.unanswered;
  report(request,
         "unanswered (no COMMAND_ACK to " + std::to_string(request.transmissions) + " requests)");
}

void MessageIntervalRequests::acknowledge(const CommandAck& ack, double now) {
  Request* waiting = in_flight();
  if (!waiting || ack.command != kMavCmdSetMessageInterval) return;
  switch (ack.result) {
    case kMavResultAccepted:
      waiting->state = State::kAccepted;
      ++counts_.accepted;
      report(*waiting, "accepted");
      return;
    case kMavResultInProgress:
      deadline_ = now + timeout_;
      return;
    case kMavResultTemporarilyRejected:
      waiting->last_result = ack.result;  // sent again when the timeout runs out
      return;
    default:
      waiting->state = State::kRefused;
      ++counts_.refused;
      report(*waiting, "refused (" + mav_result_name(ack.result) + ")");
      return;
  }
}

bool MessageIntervalRequests::done() const {
  return std::none_of(requests_.begin(), requests_.end(), [](const Request& r) {
    return r.state == State::kPending || r.state == State::kAwaitingAck;
  });
}

void MessageIntervalRequests::report(const Request& request, const std::string& outcome) {
  std::ostringstream line;
  line << "SET_MESSAGE_INTERVAL " << message_name(request.stream.message_id) << " at "
       << request.stream.rate_hz << " Hz (" << interval_us(request.stream.rate_hz)
       << " us): " << outcome;
  reports_.push_back(line.str());
}

std::vector<std::string> MessageIntervalRequests::take_reports() {
  std::vector<std::string> taken;
  taken.swap(reports_);
  return taken;
}

}  // namespace uavslam::mavlink
