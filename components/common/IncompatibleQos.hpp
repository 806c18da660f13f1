// A peer whose QoS cannot match ours is a deployment error (a wrong profile on one side), not
// something to fly on: every process checks its endpoints in its main loop and stops with a message
// naming the topic, our profile and the policy that failed (exit code 1 through run_node).
#pragma once

#include <stdexcept>
#include <string>

namespace uavslam::process {

class IncompatibleQosError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Endpoint: a dds::Reader or dds::Writer. Throws IncompatibleQosError once the endpoint has seen a
// peer whose QoS is incompatible with its own.
template <typename Endpoint>
void throw_if_incompatible(const Endpoint& endpoint) {
  if (endpoint.incompatible_qos_count() == 0) return;
  throw IncompatibleQosError("incompatible QoS on topic '" + endpoint.topic() +
                             "': a peer does not " + "match our profile '" + endpoint.profile() +
                             "' (policy " + endpoint.last_incompatible_policy() + ", " +
                             std::to_string(endpoint.incompatible_qos_count()) + " event(s))");
}

}  // namespace uavslam::process
