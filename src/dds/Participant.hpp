// A DDS participant built from a named profile of the QoS XML file, with the one Publisher and
// the one Subscriber every uavslam process needs, and the topics its writers and readers use.
//
//   dds::Participant participant(domain, dds::default_profiles_path());  // "uavslam_loopback"
//   dds::Writer<msg::LaserScanPubSubType> scans(participant, "uav1/scan", "sensor_writer");
//
// Writers and readers (Writer.hpp, Reader.hpp) should be destroyed before their Participant; one
// that outlives it is harmless (the participant deleted its entity) but must not be used.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include <fastdds/dds/core/policy/QosPolicies.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

namespace uavslam::dds {

namespace detail {
// Shared by a Participant and its endpoints: an endpoint deletes its DDS entity only while the
// participant still exists.
struct Lifetime {
  std::mutex mutex;
  bool alive = true;
};
}  // namespace detail

class Participant {
 public:
  // Loads profiles_path (load_profiles) and creates a participant on domain_id (0..232) from the
  // <participant> profile participant_profile; a non-empty name is the participant's name seen
  // by discovery tools. Throws DdsError if the file does not load, the profile is not defined
  // ("unknown participant profile '<name>' in '<path>'") or Fast DDS refuses to create it.
  Participant(int domain_id, const std::string& profiles_path,
              const std::string& participant_profile = "uavslam_loopback",
              const std::string& name = "");
  // Deletes every entity the participant contains (topics, writers, readers), then itself.
  ~Participant();

  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  // The topic `name` carrying PubSubType (a fastddsgen ...PubSubType): the type is registered
  // once per participant, the topic created once per name and reused afterwards. Throws DdsError
  // if `name` already carries another type.
  template <typename PubSubType>
  eprosima::fastdds::dds::Topic& topic(const std::string& name) {
    return topic(name, eprosima::fastdds::dds::TypeSupport(new PubSubType()));
  }
  eprosima::fastdds::dds::Topic& topic(const std::string& name,
                                       eprosima::fastdds::dds::TypeSupport type);

  int domain_id() const { return domain_id_; }
  const std::string& profiles_path() const { return profiles_path_; }
  const std::string& profile() const { return profile_; }

  eprosima::fastdds::dds::DomainParticipant& native() { return *participant_; }
  eprosima::fastdds::dds::Publisher& publisher() { return *publisher_; }
  eprosima::fastdds::dds::Subscriber& subscriber() { return *subscriber_; }
  const std::shared_ptr<detail::Lifetime>& lifetime() const { return lifetime_; }

 private:
  void destroy();

  std::string profiles_path_;
  std::string profile_;
  int domain_id_;
  std::shared_ptr<detail::Lifetime> lifetime_;
  std::mutex topics_mutex_;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
};

// "RELIABILITY", "DEADLINE", ... for the policy an incompatible-QoS event names.
std::string qos_policy_name(eprosima::fastdds::dds::QosPolicyId_t id);

namespace detail {

// Matching and incompatible-QoS state of one writer or reader, fed by its listener (on Fast DDS
// threads) and waited on by the application.
class EndpointStatus {
 public:
  void set_matched(int current_count);
  void add_incompatible_qos(std::uint32_t total_count, eprosima::fastdds::dds::QosPolicyId_t id);
  void add_received();

  std::size_t matched() const;
  bool wait_for_matched(std::size_t count, std::chrono::milliseconds timeout) const;
  std::size_t incompatible_qos_count() const;
  std::string last_incompatible_policy() const;
  bool wait_for_incompatible_qos(std::size_t count, std::chrono::milliseconds timeout) const;
  std::size_t received() const;
  bool wait_for_received(std::size_t count, std::chrono::milliseconds timeout) const;

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::size_t matched_ = 0;
  std::size_t incompatible_ = 0;
  eprosima::fastdds::dds::QosPolicyId_t last_policy_ =
      eprosima::fastdds::dds::INVALID_QOS_POLICY_ID;
  std::size_t received_ = 0;
};

// What a Writer and a Reader have in common: the topic and profile they were made with, and
// their matching and incompatible-QoS state (fed by their listeners, waited on by the application).
class Endpoint {
 public:
  const std::string& topic() const { return topic_; }
  const std::string& profile() const { return profile_; }

  // Peers currently matched, and waiting (condition variable, no polling) until at least `count`
  // are; false on timeout.
  std::size_t matched() const { return status_.matched(); }
  bool wait_for_matched(std::size_t count, std::chrono::milliseconds timeout) const {
    return status_.wait_for_matched(count, timeout);
  }

  // Peers found on the topic whose QoS cannot match ours, in total, and the policy that failed
  // last ("RELIABILITY", "DURABILITY", "DEADLINE", ...).
  std::size_t incompatible_qos_count() const { return status_.incompatible_qos_count(); }
  std::string last_incompatible_policy() const { return status_.last_incompatible_policy(); }
  bool wait_for_incompatible_qos(std::size_t count, std::chrono::milliseconds timeout) const {
    return status_.wait_for_incompatible_qos(count, timeout);
  }

 protected:
  Endpoint(std::string topic, std::string profile)
      : topic_(std::move(topic)), profile_(std::move(profile)) {}

  EndpointStatus status_;

 private:
  std::string topic_;
  std::string profile_;
};

// Create / delete the DDS entities of Writer and Reader (non-template parts). Creation throws
// DdsError "unknown writer profile '<profile>' for topic '<topic>' in '<path>'" (reader alike).
eprosima::fastdds::dds::DataWriter* create_writer(
    Participant& participant, eprosima::fastdds::dds::Topic& topic, const std::string& profile,
    eprosima::fastdds::dds::DataWriterListener* listener);
eprosima::fastdds::dds::DataReader* create_reader(
    Participant& participant, eprosima::fastdds::dds::Topic& topic, const std::string& profile,
    eprosima::fastdds::dds::DataReaderListener* listener);
void delete_writer(const std::shared_ptr<Lifetime>& lifetime,
                   eprosima::fastdds::dds::Publisher* publisher,
                   eprosima::fastdds::dds::DataWriter* writer);
void delete_reader(const std::shared_ptr<Lifetime>& lifetime,
                   eprosima::fastdds::dds::Subscriber* subscriber,
                   eprosima::fastdds::dds::DataReader* reader);

}  // namespace detail

}  // namespace uavslam::dds
