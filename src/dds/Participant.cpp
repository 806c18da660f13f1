#include "dds/Participant.hpp"

#include <chrono>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/publisher/qos/PublisherQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/subscriber/qos/SubscriberQos.hpp>
#include <fastdds/dds/topic/qos/TopicQos.hpp>

#include "dds/DdsError.hpp"
#include "dds/LinkInterfaces.hpp"
#include "dds/Profiles.hpp"

namespace uavslam::dds {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

constexpr int kMaxDomainId = 232;  // the largest id whose ports fit Fast DDS's default port mapping
constexpr std::chrono::seconds kInterfaceWait{30};  // for a link interface that is not up yet

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) {
    if (!out.empty()) out += ", ";
    out += "'" + name + "'";
  }
  return out;
}

// " (data_writer profiles there: 'a', 'b')" when the file names any, for error messages.
std::string known_profiles(const std::string& path, const std::string& element) {
  const std::vector<std::string> names = profile_names(path, element);
  if (names.empty()) return "";
  return " (" + element + " profiles there: " + quoted_list(names) + ")";
}

}  // namespace

Participant::Participant(int domain_id, const std::string& profiles_path,
                         const std::string& participant_profile, const std::string& name)
    : profiles_path_(profiles_path),
      profile_(participant_profile),
      domain_id_(domain_id),
      lifetime_(std::make_shared<detail::Lifetime>()) {
  if (domain_id < 0 || domain_id > kMaxDomainId) {
    throw DdsError("DDS domain id " + std::to_string(domain_id) + " is outside 0.." +
                   std::to_string(kMaxDomainId));
  }
  load_profiles(profiles_path);

  auto* factory = fdds::DomainParticipantFactory::get_instance();
  fdds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile(participant_profile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw DdsError("unknown participant profile '" + participant_profile + "' in '" +
                   profiles_path + "'" + known_profiles(profiles_path, "participant"));
  }
  wait_for_link_interfaces(qos, participant_profile, kInterfaceWait);
  const auto domain = static_cast<fdds::DomainId_t>(domain_id);
  if (name.empty()) {
    participant_ = factory->create_participant_with_profile(domain, participant_profile);
  } else {
    qos.name(name);  // the same profile, only the name differs
    participant_ = factory->create_participant(domain, qos);
  }
  if (participant_ == nullptr) {
    throw DdsError("cannot create a DDS participant on domain " + std::to_string(domain_id) +
                   " from profile '" + participant_profile + "' in '" + profiles_path +
                   "' (see the Fast DDS log)");
  }
  publisher_ = participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    destroy();
    throw DdsError("cannot create the publisher and subscriber of the participant from '" +
                   participant_profile + "' in '" + profiles_path + "'");
  }
}

Participant::~Participant() {
  destroy();
}

void Participant::destroy() {
  std::lock_guard<std::mutex> lock(lifetime_->mutex);
  lifetime_->alive = false;
  if (participant_ == nullptr) return;
  participant_->delete_contained_entities();
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  participant_ = nullptr;
  publisher_ = nullptr;
  subscriber_ = nullptr;
}

fdds::Topic& Participant::topic(const std::string& name, fdds::TypeSupport type) {
  std::lock_guard<std::mutex> lock(topics_mutex_);
  const std::string type_name = type.get_type_name();
  if (participant_->find_type(type_name).empty()) {
    if (type.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
      throw DdsError("cannot register type '" + type_name + "' for topic '" + name + "'");
    }
  }
  if (fdds::TopicDescription* existing = participant_->lookup_topicdescription(name)) {
    if (existing->get_type_name() != type_name) {
      throw DdsError("topic '" + name + "' already carries type '" + existing->get_type_name() +
                     "', not '" + type_name + "'");
    }
    auto* topic = dynamic_cast<fdds::Topic*>(existing);
    if (topic == nullptr) throw DdsError("'" + name + "' is not a plain topic");
    return *topic;
  }
  fdds::Topic* topic = participant_->create_topic(name, type_name, fdds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr) {
    throw DdsError("cannot create topic '" + name + "' of type '" + type_name + "'");
  }
  return *topic;
}

std::string qos_policy_name(fdds::QosPolicyId_t id) {
  switch (id) {
    case fdds::USERDATA_QOS_POLICY_ID:
      return "USER_DATA";
    case fdds::DURABILITY_QOS_POLICY_ID:
      return "DURABILITY";
    case fdds::PRESENTATION_QOS_POLICY_ID:
      return "PRESENTATION";
    case fdds::DEADLINE_QOS_POLICY_ID:
      return "DEADLINE";
    case fdds::LATENCYBUDGET_QOS_POLICY_ID:
      return "LATENCY_BUDGET";
    case fdds::OWNERSHIP_QOS_POLICY_ID:
      return "OWNERSHIP";
    case fdds::OWNERSHIPSTRENGTH_QOS_POLICY_ID:
      return "OWNERSHIP_STRENGTH";
    case fdds::LIVELINESS_QOS_POLICY_ID:
      return "LIVELINESS";
    case fdds::TIMEBASEDFILTER_QOS_POLICY_ID:
      return "TIME_BASED_FILTER";
    case fdds::PARTITION_QOS_POLICY_ID:
      return "PARTITION";
    case fdds::RELIABILITY_QOS_POLICY_ID:
      return "RELIABILITY";
    case fdds::DESTINATIONORDER_QOS_POLICY_ID:
      return "DESTINATION_ORDER";
    case fdds::HISTORY_QOS_POLICY_ID:
      return "HISTORY";
    case fdds::RESOURCELIMITS_QOS_POLICY_ID:
      return "RESOURCE_LIMITS";
    case fdds::LIFESPAN_QOS_POLICY_ID:
      return "LIFESPAN";
    case fdds::DURABILITYSERVICE_QOS_POLICY_ID:
      return "DURABILITY_SERVICE";
    case fdds::DATAREPRESENTATION_QOS_POLICY_ID:
      return "DATA_REPRESENTATION";
    case fdds::TYPECONSISTENCYENFORCEMENT_QOS_POLICY_ID:
      return "TYPE_CONSISTENCY_ENFORCEMENT";
    case fdds::DISABLEPOSITIVEACKS_QOS_POLICY_ID:
      return "DISABLE_POSITIVE_ACKS";
    case fdds::PUBLISHMODE_QOS_POLICY_ID:
      return "PUBLISH_MODE";
    case fdds::INVALID_QOS_POLICY_ID:
      return "";
    default:
      return "QOS_POLICY_" + std::to_string(static_cast<int>(id));
  }
}

namespace detail {

void EndpointStatus::set_matched(int current_count) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    matched_ = current_count > 0 ? static_cast<std::size_t>(current_count) : 0;
  }
  changed_.notify_all();
}

void EndpointStatus::add_incompatible_qos(std::uint32_t total_count, fdds::QosPolicyId_t id) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    incompatible_ = total_count;
    last_policy_ = id;
  }
  changed_.notify_all();
}

void EndpointStatus::add_received() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++received_;
  }
  changed_.notify_all();
}

std::size_t EndpointStatus::matched() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return matched_;
}

bool EndpointStatus::wait_for_matched(std::size_t count, std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return changed_.wait_for(lock, timeout, [&] { return matched_ >= count; });
}

std::size_t EndpointStatus::incompatible_qos_count() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return incompatible_;
}

std::string EndpointStatus::last_incompatible_policy() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return qos_policy_name(last_policy_);
}

bool EndpointStatus::wait_for_incompatible_qos(std::size_t count,
                                               std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return changed_.wait_for(lock, timeout, [&] { return incompatible_ >= count; });
}

std::size_t EndpointStatus::received() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return received_;
}

bool EndpointStatus::wait_for_received(std::size_t count, std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return changed_.wait_for(lock, timeout, [&] { return received_ >= count; });
}

fdds::DataWriter* create_writer(Participant& participant, fdds::Topic& topic,
                                const std::string& profile, fdds::DataWriterListener* listener) {
  fdds::DataWriterQos qos;
  if (participant.publisher().get_datawriter_qos_from_profile(profile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw DdsError("unknown writer profile '" + profile + "' for topic '" + topic.get_name() +
                   "' in '" + participant.profiles_path() + "'" +
                   known_profiles(participant.profiles_path(), "data_writer"));
  }
  fdds::DataWriter* writer =
      participant.publisher().create_datawriter_with_profile(&topic, profile, listener);
  if (writer == nullptr) {
    throw DdsError("cannot create a writer for topic '" + topic.get_name() + "' from profile '" +
                   profile + "' in '" + participant.profiles_path() +
                   "': Fast DDS refused its QoS (see its log)");
  }
  return writer;
}

fdds::DataReader* create_reader(Participant& participant, fdds::Topic& topic,
                                const std::string& profile, fdds::DataReaderListener* listener) {
  fdds::DataReaderQos qos;
  if (participant.subscriber().get_datareader_qos_from_profile(profile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw DdsError("unknown reader profile '" + profile + "' for topic '" + topic.get_name() +
                   "' in '" + participant.profiles_path() + "'" +
                   known_profiles(participant.profiles_path(), "data_reader"));
  }
  fdds::DataReader* reader =
      participant.subscriber().create_datareader_with_profile(&topic, profile, listener);
  if (reader == nullptr) {
    throw DdsError("cannot create a reader for topic '" + topic.get_name() + "' from profile '" +
                   profile + "' in '" + participant.profiles_path() +
                   "': Fast DDS refused its QoS (see its log)");
  }
  return reader;
}

void delete_writer(const std::shared_ptr<Lifetime>& lifetime, fdds::Publisher* publisher,
                   fdds::DataWriter* writer) {
  std::lock_guard<std::mutex> lock(lifetime->mutex);
  if (!lifetime->alive || writer == nullptr) return;
  writer->set_listener(nullptr);
  publisher->delete_datawriter(writer);
}

void delete_reader(const std::shared_ptr<Lifetime>& lifetime, fdds::Subscriber* subscriber,
                   fdds::DataReader* reader) {
  std::lock_guard<std::mutex> lock(lifetime->mutex);
  if (!lifetime->alive || reader == nullptr) return;
  reader->set_listener(nullptr);
  subscriber->delete_datareader(reader);
}

}  // namespace detail

}  // namespace uavslam::dds
