// A typed DDS writer on one topic, with its QoS from a <data_writer> profile of the participant's
// XML file ("sensor_writer", "state_writer", "map_points_writer", "map_writer", "status_writer").
// The template parameter is the fastddsgen ...PubSubType (msg::LaserScanPubSubType), not the
// message type itself.
//
//   dds::Writer<msg::LaserScanPubSubType> scans(participant, topic_name(vehicle, kScanTopic),
//                                               "sensor_writer");
//   scans.write(scan);
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include "dds/Participant.hpp"

namespace uavslam::dds {

template <typename PubSubType>
class Writer : public detail::Endpoint {
 public:
  using Sample = typename PubSubType::type;

  // Creates the writer on `topic` (created on first use) with the QoS of `profile`. Throws
  // DdsError "unknown writer profile '<profile>' for topic '<topic>' in '<path>'" when the
  // profile is not defined, or when Fast DDS refuses the writer.
  Writer(Participant& participant, const std::string& topic, const std::string& profile)
      : detail::Endpoint(topic, profile),
        lifetime_(participant.lifetime()),
        publisher_(&participant.publisher()) {
    writer_ = detail::create_writer(participant, participant.topic<PubSubType>(topic), profile,
                                    &listener_);
  }
  ~Writer() { detail::delete_writer(lifetime_, publisher_, writer_); }

  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Publishes one sample; false if Fast DDS did not accept it (a RELIABLE writer whose history
  // stayed full for the profile's max_blocking_time, for example).
  bool write(const Sample& sample) {
    // DataWriter::write takes void*; it does not modify the sample.
    return writer_->write(const_cast<Sample*>(&sample));
  }

  // Blocks until every matched reliable reader acknowledged every sample written so far, or
  // `timeout` passed (false then). Call before a process exits so its last samples are not lost
  // with the writer.
  bool wait_for_acknowledgments(std::chrono::milliseconds timeout) {
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(timeout).count();
    const eprosima::fastrtps::Duration_t max_wait(static_cast<int32_t>(ns / 1000000000),
                                                  static_cast<uint32_t>(ns % 1000000000));
    return writer_->wait_for_acknowledgments(max_wait) == ReturnCode_t::RETCODE_OK;
  }

  eprosima::fastdds::dds::DataWriter& native() { return *writer_; }

 private:
  using ReturnCode_t = eprosima::fastrtps::types::ReturnCode_t;

  // Called on Fast DDS threads.
  class Listener : public eprosima::fastdds::dds::DataWriterListener {
   public:
    explicit Listener(detail::EndpointStatus& status) : status_(status) {}
    void on_publication_matched(
        eprosima::fastdds::dds::DataWriter*,
        const eprosima::fastdds::dds::PublicationMatchedStatus& info) override {
      status_.set_matched(info.current_count);
    }
    void on_offered_incompatible_qos(
        eprosima::fastdds::dds::DataWriter*,
        const eprosima::fastdds::dds::OfferedIncompatibleQosStatus& info) override {
      status_.add_incompatible_qos(info.total_count, info.last_policy_id);
    }

   private:
    detail::EndpointStatus& status_;
  };

  std::shared_ptr<detail::Lifetime> lifetime_;
  eprosima::fastdds::dds::Publisher* publisher_;
  Listener listener_{status_};
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
};

}  // namespace uavslam::dds
