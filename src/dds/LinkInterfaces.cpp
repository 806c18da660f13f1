#include "dds/LinkInterfaces.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>

#include <algorithm>
#include <iostream>
#include <thread>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>

#include "dds/DdsError.hpp"

namespace uavslam::dds {
namespace {

std::vector<std::string> running_ipv4_addresses() {
  std::vector<std::string> found;
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return found;
  for (const ifaddrs* i = list; i != nullptr; i = i->ifa_next) {
    if (i->ifa_addr == nullptr || i->ifa_addr->sa_family != AF_INET) continue;
    if ((i->ifa_flags & IFF_RUNNING) == 0) continue;
    char text[INET_ADDRSTRLEN];
    const auto* address = reinterpret_cast<const sockaddr_in*>(i->ifa_addr);
    if (inet_ntop(AF_INET, &address->sin_addr, text, sizeof text)) found.emplace_back(text);
  }
  freeifaddrs(list);
  return found;
}

std::string joined(const std::vector<std::string>& values) {
  std::string text;
  for (const std::string& v : values) text += (text.empty() ? "" : ", ") + v;
  return text;
}

}  // namespace

std::vector<std::string> whitelisted_addresses(
    const eprosima::fastdds::dds::DomainParticipantQos& qos) {
  std::vector<std::string> addresses;
  for (const auto& descriptor : qos.transport().user_transports) {
    const auto* udp =
        dynamic_cast<const eprosima::fastdds::rtps::UDPv4TransportDescriptor*>(descriptor.get());
    if (udp == nullptr) continue;
    addresses.insert(addresses.end(), udp->interfaceWhiteList.begin(),
                     udp->interfaceWhiteList.end());
  }
  return addresses;
}

std::vector<std::string> addresses_not_running(const std::vector<std::string>& addresses) {
  const std::vector<std::string> running = running_ipv4_addresses();
  std::vector<std::string> missing;
  for (const std::string& a : addresses) {
    if (std::find(running.begin(), running.end(), a) == running.end()) missing.push_back(a);
  }
  return missing;
}

void wait_for_link_interfaces(const eprosima::fastdds::dds::DomainParticipantQos& qos,
                              const std::string& profile, std::chrono::seconds timeout) {
  const std::vector<std::string> addresses = whitelisted_addresses(qos);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  bool said = false;
  for (std::vector<std::string> missing = addresses_not_running(addresses); !missing.empty();
       missing = addresses_not_running(addresses)) {
    if (std::chrono::steady_clock::now() > deadline) {
      throw DdsError("no running interface has the address(es) " + joined(missing) +
                     " that participant profile '" + profile + "' sends from, after " +
                     std::to_string(timeout.count()) + " s");
    }
    if (!said) {
      std::cerr << "waiting for an interface with " << joined(missing)
                << " to run (participant profile '" << profile << "')\n";
      said = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

}  // namespace uavslam::dds
