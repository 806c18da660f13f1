// A peer whose QoS cannot match ours is a deployment error (a wrong profile on one side). Each
// process checks its endpoints in its main loop:
// - an input (a reader the process needs) that a writer cannot serve stops the process with a
//   message naming the topic, our profile and the failed policy: it has nothing to work on;
// - an output (a writer) that some reader asks more of is reported once per new event and the
//   process goes on serving the readers that match, so a misconfigured ground tool cannot stop the
//   vehicle's processes; the process then exits 1 at its end (QosWatch::exit_code).
#pragma once

#include <cstddef>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>

namespace uavslam::process {

class IncompatibleQosError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "incompatible QoS on topic 'uav1/scan': a peer does not match our profile 'sensor_reader'
// (policy RELIABILITY, 1 event(s))". Endpoint: a dds::Reader or dds::Writer.
template <typename Endpoint>
std::string incompatible_qos_message(const Endpoint& endpoint) {
  return "incompatible QoS on topic '" + endpoint.topic() +
         "': a peer does not match our profile '" + endpoint.profile() + "' (policy " +
         endpoint.last_incompatible_policy() + ", " +
         std::to_string(endpoint.incompatible_qos_count()) + " event(s))";
}

// Throws IncompatibleQosError once the endpoint has seen a peer whose QoS is incompatible.
template <typename Endpoint>
void throw_if_incompatible(const Endpoint& endpoint) {
  if (endpoint.incompatible_qos_count() > 0) {
    throw IncompatibleQosError(incompatible_qos_message(endpoint));
  }
}

class QosWatch {
 public:
  explicit QosWatch(std::string process) : process_(std::move(process)) {}

  template <typename Reader>
  void input(const Reader& reader) const {
    throw_if_incompatible(reader);
  }

  template <typename Writer>
  void output(const Writer& writer) {
    const std::size_t count = writer.incompatible_qos_count();
    std::size_t& reported = reported_[writer.topic()];
    if (count <= reported) return;
    reported = count;
    std::cerr << process_ << ": " << incompatible_qos_message(writer)
              << "; serving the readers that match\n";
  }

  // 1 when an output met an incompatible reader during the run, else `ok`.
  int exit_code(int ok = 0) const {
    for (const auto& topic : reported_) {
      if (topic.second > 0) return 1;
    }
    return ok;
  }

 private:
  std::string process_;
  std::map<std::string, std::size_t> reported_;
};

}  // namespace uavslam::process
