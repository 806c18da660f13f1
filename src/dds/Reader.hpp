// A typed DDS reader on one topic, with its QoS from a <data_reader> profile of the participant's
// XML file ("sensor_reader", "state_reader", "map_points_reader", "map_reader", "status_reader"),
// handing every received sample to a callback.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>

#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "dds/Participant.hpp"

namespace uavslam::dds {

template <typename PubSubType>
class Reader : public detail::Endpoint {
 public:
  using Sample = typename PubSubType::type;
  using Callback =
      std::function<void(const Sample& sample, const eprosima::fastdds::dds::SampleInfo& info)>;

  // Creates the reader on `topic` (created on first use) with the QoS of `profile`. on_sample is
  // called for every sample with data, in order, ON A FAST DDS THREAD (the reader's receive
  // thread): keep it short, guard what it shares with other threads, and do not throw (an
  // exception is swallowed and counted in callback_errors()). It may already run before this
  // constructor returns. Throws DdsError "unknown reader profile '<profile>' for topic '<topic>'
  // in '<path>'" when the profile is not defined, or when Fast DDS refuses the reader.
  Reader(Participant& participant, const std::string& topic, const std::string& profile,
         Callback on_sample)
      : detail::Endpoint(topic, profile),
        lifetime_(participant.lifetime()),
        subscriber_(&participant.subscriber()),
        on_sample_(std::move(on_sample)) {
    reader_ = detail::create_reader(participant, participant.topic<PubSubType>(topic), profile,
                                    &listener_);
  }
  ~Reader() { detail::delete_reader(lifetime_, subscriber_, reader_); }

  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  // Samples handed to the callback so far (counted after it returns), and waiting until at least
  // `count` were; false on timeout.
  std::size_t received() const { return status_.received(); }
  bool wait_for_received(std::size_t count, std::chrono::milliseconds timeout) const {
    return status_.wait_for_received(count, timeout);
  }
  std::size_t callback_errors() const { return callback_errors_; }

  eprosima::fastdds::dds::DataReader& native() { return *reader_; }

 private:
  // Called on Fast DDS threads.
  class Listener : public eprosima::fastdds::dds::DataReaderListener {
   public:
    explicit Listener(Reader& owner) : owner_(owner) {}
    void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
      Sample sample;
      eprosima::fastdds::dds::SampleInfo info;
      while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
        if (!info.valid_data) continue;  // instance state changes carry no data
        try {
          if (owner_.on_sample_) owner_.on_sample_(sample, info);
        } catch (...) {
          ++owner_.callback_errors_;
        }
        owner_.status_.add_received();
      }
    }
    void on_subscription_matched(
        eprosima::fastdds::dds::DataReader*,
        const eprosima::fastdds::dds::SubscriptionMatchedStatus& info) override {
      owner_.status_.set_matched(info.current_count);
    }
    void on_requested_incompatible_qos(
        eprosima::fastdds::dds::DataReader*,
        const eprosima::fastdds::dds::RequestedIncompatibleQosStatus& info) override {
      owner_.status_.add_incompatible_qos(info.total_count, info.last_policy_id);
    }

   private:
    using ReturnCode_t = eprosima::fastrtps::types::ReturnCode_t;
    Reader& owner_;
  };

  std::shared_ptr<detail::Lifetime> lifetime_;
  eprosima::fastdds::dds::Subscriber* subscriber_;
  Callback on_sample_;
  std::atomic<std::size_t> callback_errors_{0};
  Listener listener_{*this};
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
};

}  // namespace uavslam::dds
