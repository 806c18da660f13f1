// A participant whose UDP transport is whitelisted to one interface (the link profiles) must not
// start before that interface runs: Fast DDS leaves a whitelisted interface that is not running
// out of the transport for good ("All whitelist interfaces were filtered out"), and the process
// then never reaches the other host. Measured on a veth pair: a ground station started while its
// interface's carrier was still coming up discovered nothing in 30 s. A vehicle's WiFi joining
// after boot is the same case, so the participant waits for its interfaces first.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

namespace uavslam::dds {

// The addresses the profile's UDPv4 transports are whitelisted to.
std::vector<std::string> whitelisted_addresses(
    const eprosima::fastdds::dds::DomainParticipantQos& qos);

// Those of `addresses` that no running interface of this host carries.
std::vector<std::string> addresses_not_running(const std::vector<std::string>& addresses);

// Waits until every whitelisted address is on a running interface, saying once on stderr what it
// waits for; throws DdsError naming the addresses and `profile` after `timeout`.
void wait_for_link_interfaces(const eprosima::fastdds::dds::DomainParticipantQos& qos,
                              const std::string& profile, std::chrono::seconds timeout);

}  // namespace uavslam::dds
