// Asking the autopilot for the message streams we need, by the MAVLink command protocol
// (mavlink.io/en/services/command.html): one MAV_CMD_SET_MESSAGE_INTERVAL in a COMMAND_LONG per
// wanted message (param1 its id, param2 the interval in us), sent one at a time, because a
// COMMAND_ACK names the command but not its parameters. ACCEPTED: done. IN_PROGRESS: wait on.
// TEMPORARILY_REJECTED or no answer within the timeout: sent again with the confirmation field
// counting up, up to `attempts` transmissions, then given up. Any other result (DENIED,
// UNSUPPORTED, FAILED, ...): refused, not retried. Each outcome is reported once, as a line of
// text for the operator. Transport-independent: the caller sends the commands and gives the time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "drivers/mavlink/Messages.hpp"

namespace uavslam::mavlink {

struct StreamRequest {
  std::uint16_t message_id = 0;
  double rate_hz = 0;  // > 0
};

struct IntervalRequestCounts {
  std::uint64_t sent = 0;        // COMMAND_LONGs, resends included
  std::uint64_t accepted = 0;    // messages
  std::uint64_t refused = 0;     // messages the autopilot said no to
  std::uint64_t unanswered = 0;  // messages given up on without an answer
};

class MessageIntervalRequests {
 public:
  using SendCommand = std::function<void(const CommandLong&)>;

  MessageIntervalRequests(std::vector<StreamRequest> wanted, double timeout, int attempts);

  // Asks (again, after a reboot) for every wanted stream, from the autopilot's ids.
  void start(std::uint8_t target_system, std::uint8_t target_component);
  // Sends what is due at `now` (s): the next request, or a resend after the timeout.
  void tick(double now, const SendCommand& send);
  // An answer from the autopilot; anything but one to SET_MESSAGE_INTERVAL in flight is ignored.
  void acknowledge(const CommandAck& ack, double now);

  bool done() const;  // every wanted stream answered or given up
  const IntervalRequestCounts& counts() const { return counts_; }
  // The outcome lines since the last call.
  std::vector<std::string> take_reports();

 private:
  enum class State { kPending, kAwaitingAck, kAccepted, kRefused, kUnanswered };
  struct Request {
    explicit Request(const StreamRequest& wanted) : stream(wanted) {}
    StreamRequest stream;
    State state = State::kPending;
    int transmissions = 0;
    std::optional<std::uint8_t> last_result;  // TEMPORARILY_REJECTED, before the timeout
  };

  void transmit(Request& request, double now, const SendCommand& send);
  void give_up(Request& request);
  void report(const Request& request, const std::string& outcome);
  Request* in_flight();

  std::vector<Request> requests_;
  double timeout_;
  int attempts_;
  std::uint8_t target_system_ = 0;
  std::uint8_t target_component_ = 0;
  bool started_ = false;
  double deadline_ = 0;  // of the request in flight
  IntervalRequestCounts counts_;
  std::vector<std::string> reports_;
};

// The interval param2 carries for `rate_hz`, in us.
float interval_us(double rate_hz);

}  // namespace uavslam::mavlink
