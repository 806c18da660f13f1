// The QoS profile file: it loads, it defines every profile the processes use, the default
// participant keeps DDS on loopback, and every way of getting it wrong is a DdsError that names
// the file or the profile.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <msg/LaserScanPubSubTypes.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include "dds/DdsError.hpp"
#include "dds/LinkInterfaces.hpp"
#include "dds/Participant.hpp"
#include "dds/Profiles.hpp"
#include "dds/Reader.hpp"
#include "dds/Writer.hpp"

namespace uavslam::dds {
namespace {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;
using testing::AllOf;
using testing::HasSubstr;
using testing::IsSupersetOf;

const std::vector<std::string> kClasses{"sensor",     "sensor_link", "state",
                                        "map_points", "map",         "status"};

// A QoS file written by the test, removed afterwards.
class TempXml {
 public:
  TempXml(const std::string& name, const std::string& text)
      : path_(testing::TempDir() + "uavslam_qos_" + name + ".xml") {
    std::ofstream(path_) << text;
  }
  ~TempXml() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const DdsError& e) {
    return e.what();
  }
  return "(no DdsError)";
}

TEST(QosProfiles, TheShippedFileLoads) {
  EXPECT_NO_THROW(load_profiles(default_profiles_path()));
  EXPECT_NO_THROW(load_profiles(default_profiles_path())) << "a second load is a no-op";
}

TEST(QosProfiles, TheShippedFileNamesEveryClassAndTheLoopbackParticipant) {
  const std::string path = default_profiles_path();
  EXPECT_THAT(profile_names(path, "participant"),
              testing::UnorderedElementsAre("uavslam_loopback", "uavslam_link_uav",
                                            "uavslam_link_gcs", "uavslam_link_uav_client",
                                            "uavslam_link_gcs_client", "uavslam_discovery_server"));
  std::vector<std::string> writers, readers;
  for (const std::string& c : kClasses) {
    writers.push_back(c + "_writer");
    readers.push_back(c + "_reader");
  }
  EXPECT_THAT(profile_names(path, "data_writer"), IsSupersetOf(writers));
  EXPECT_THAT(profile_names(path, "data_reader"), IsSupersetOf(readers));
}

// Every profile the file declares (by the text scan of profile_names) is one Fast DDS knows, so
// the names in error messages and the profiles really loaded cannot drift apart. Asked of Fast
// DDS's profile store directly: no participant, no traffic.
TEST(QosProfiles, EveryDeclaredProfileIsDefinedInFastDds) {
  using eprosima::fastrtps::xmlparser::XMLP_ret;
  using eprosima::fastrtps::xmlparser::XMLProfileManager;
  const std::string path = default_profiles_path();
  load_profiles(path);
  for (const std::string& name : profile_names(path, "participant")) {
    eprosima::fastrtps::ParticipantAttributes attributes;
    EXPECT_EQ(XMLProfileManager::fillParticipantAttributes(name, attributes), XMLP_ret::XML_OK)
        << name;
  }
  for (const std::string& name : profile_names(path, "data_writer")) {
    eprosima::fastrtps::PublisherAttributes attributes;
    EXPECT_EQ(XMLProfileManager::fillPublisherAttributes(name, attributes), XMLP_ret::XML_OK)
        << name;
  }
  for (const std::string& name : profile_names(path, "data_reader")) {
    eprosima::fastrtps::SubscriberAttributes attributes;
    EXPECT_EQ(XMLProfileManager::fillSubscriberAttributes(name, attributes), XMLP_ret::XML_OK)
        << name;
  }
}

// The network rule as configuration: no built-in transports, shared memory, and UDP only on
// 127.0.0.1 (tcpdump confirms it on the wire: test/net/check_loopback_only.sh).
// What a participant profile may send through: its shared-memory transports, and the interface
// whitelist of each UDPv4 transport (an empty whitelist would mean every interface).
struct ProfileTransports {
  bool builtin = true;
  int shm = 0;
  std::vector<std::vector<std::string>> udp_whitelists;
  int other = 0;
};

ProfileTransports transports_of(const std::string& profile) {
  load_profiles(default_profiles_path());
  fdds::DomainParticipantQos qos;
  EXPECT_EQ(fdds::DomainParticipantFactory::get_instance()->get_participant_qos_from_profile(
                profile, qos),
            ReturnCode_t::RETCODE_OK)
      << profile;
  ProfileTransports t;
  t.builtin = qos.transport().use_builtin_transports;
  for (const auto& descriptor : qos.transport().user_transports) {
    if (dynamic_cast<eprosima::fastdds::rtps::SharedMemTransportDescriptor*>(descriptor.get())) {
      ++t.shm;
    } else if (const auto* u = dynamic_cast<eprosima::fastdds::rtps::UDPv4TransportDescriptor*>(
                   descriptor.get())) {
      t.udp_whitelists.push_back(u->interfaceWhiteList);
    } else {
      ++t.other;
    }
  }
  return t;
}

TEST(QosProfiles, TheDefaultParticipantUsesLoopbackTransportsOnly) {
  const ProfileTransports t = transports_of("uavslam_loopback");
  EXPECT_FALSE(t.builtin);
  EXPECT_EQ(t.shm, 1);
  EXPECT_EQ(t.other, 0);
  EXPECT_THAT(t.udp_whitelists, testing::ElementsAre(std::vector<std::string>{"127.0.0.1"}));
}

// The network rule on a link: UDP only on the link's own address (the emulated link's, which the
// two-host tests build inside network namespaces), never an open whitelist.
TEST(QosProfiles, TheLinkParticipantsSendOnTheLinkAddressOnly) {
  const std::vector<std::pair<std::string, std::string>> link{
      {"uavslam_link_uav", "10.200.0.1"},
      {"uavslam_link_gcs", "10.200.0.2"},
      {"uavslam_link_uav_client", "10.200.0.1"},
      {"uavslam_link_gcs_client", "10.200.0.2"},
      {"uavslam_discovery_server", "10.200.0.1"}};
  for (const auto& [profile, address] : link) {
    const ProfileTransports t = transports_of(profile);
    EXPECT_FALSE(t.builtin) << profile;
    EXPECT_EQ(t.other, 0) << profile;
    EXPECT_THAT(t.udp_whitelists, testing::ElementsAre(std::vector<std::string>{address}))
        << profile;
  }
}

// A link datagram fits one WiFi frame (MTU 1500 less the IP and UDP headers), so a lost frame
// costs one fragment, which a RELIABLE writer resends.
TEST(QosProfiles, TheLinkTransportsKeepDatagramsUnderTheWifiMtu) {
  load_profiles(default_profiles_path());
  fdds::DomainParticipantQos qos;
  ASSERT_EQ(fdds::DomainParticipantFactory::get_instance()->get_participant_qos_from_profile(
                "uavslam_link_uav", qos),
            ReturnCode_t::RETCODE_OK);
  int udp = 0;
  for (const auto& descriptor : qos.transport().user_transports) {
    if (const auto* u =
            dynamic_cast<eprosima::fastdds::rtps::UDPv4TransportDescriptor*>(descriptor.get())) {
      ++udp;
      EXPECT_LE(u->maxMessageSize, 1472u);
    }
  }
  EXPECT_EQ(udp, 1);
}

// The link profiles wait for their interface: on this host (no 10.200.0.x) the wait ends with an
// error naming the address and the profile; the loopback profile's address always runs.
TEST(QosProfiles, ALinkParticipantWaitsForItsInterfaceThenNamesIt) {
  load_profiles(default_profiles_path());
  fdds::DomainParticipantQos qos;
  ASSERT_EQ(fdds::DomainParticipantFactory::get_instance()->get_participant_qos_from_profile(
                "uavslam_link_uav", qos),
            ReturnCode_t::RETCODE_OK);
  EXPECT_EQ(whitelisted_addresses(qos), std::vector<std::string>{"10.200.0.1"});
  if (addresses_not_running({"10.200.0.1"}).empty()) GTEST_SKIP() << "this host has 10.200.0.1";
  EXPECT_THAT(
      error_of([&] { wait_for_link_interfaces(qos, "uavslam_link_uav", std::chrono::seconds(1)); }),
      AllOf(HasSubstr("10.200.0.1"), HasSubstr("'uavslam_link_uav'")));
  EXPECT_TRUE(addresses_not_running({"127.0.0.1"}).empty());
}

TEST(QosProfiles, AMalformedFileIsADdsErrorNamingIt) {
  const TempXml broken("malformed", "<dds><profiles><participant profile_name=\"p\">");
  EXPECT_THAT(error_of([&] { load_profiles(broken.path()); }),
              HasSubstr("cannot load QoS profiles from '" + broken.path() + "'"));
}

TEST(QosProfiles, ABadValueIsADdsErrorNamingTheFile) {
  const TempXml bad_value(
      "bad_value",
      "<dds><profiles xmlns=\"http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles\">"
      "<data_writer profile_name=\"w\"><qos><reliability><kind>SOMETIMES</kind></reliability>"
      "</qos></data_writer></profiles></dds>");
  EXPECT_THAT(error_of([&] { load_profiles(bad_value.path()); }), HasSubstr(bad_value.path()));
}

TEST(QosProfiles, AMissingFileIsADdsErrorNamingIt) {
  const std::string missing = testing::TempDir() + "uavslam_no_such_profiles.xml";
  EXPECT_THAT(error_of([&] { load_profiles(missing); }),
              HasSubstr("'" + missing + "': no such file"));
}

TEST(QosProfiles, AnUnknownParticipantProfileIsADdsErrorNamingIt) {
  // The profile is checked before anything joins the domain.
  const std::string message = error_of(
      [] { Participant participant(178, default_profiles_path(), "no_such_participant"); });
  EXPECT_THAT(message, HasSubstr("unknown participant profile 'no_such_participant'"));
  EXPECT_THAT(message, HasSubstr("'uavslam_loopback'")) << "lists the profiles there";
}

TEST(QosProfiles, UnknownWriterAndReaderProfilesAreDdsErrorsNamingThem) {
  Participant participant(178, default_profiles_path());
  const std::string writer_error = error_of([&] {
    Writer<msg::LaserScanPubSubType> writer(participant, "qos_test/unknown", "no_such_writer");
  });
  EXPECT_THAT(writer_error, HasSubstr("unknown writer profile 'no_such_writer'"));
  EXPECT_THAT(writer_error, HasSubstr("'sensor_writer'")) << "lists the profiles there";
  const std::string reader_error = error_of([&] {
    Reader<msg::LaserScanPubSubType> reader(participant, "qos_test/unknown", "no_such_reader",
                                            nullptr);
  });
  EXPECT_THAT(reader_error, HasSubstr("unknown reader profile 'no_such_reader'"));
  EXPECT_THAT(reader_error, HasSubstr("'sensor_reader'"));
}

}  // namespace
}  // namespace uavslam::dds
