#include "common/McapReplay.hpp"

#include <iostream>

#include "common/StopRequest.hpp"
#include "dds/Topics.hpp"

namespace uavslam::process {

std::set<std::string> recorded_topics(const std::string& vehicle, const std::string& base) {
  return {base, dds::topic_name(vehicle, base)};
}

void print_new_problems(dds::RecordedMessageStream& stream, const char* process) {
  for (const std::string& problem : stream.take_new_problems()) {
    std::cerr << process << ": skipped " << problem << "\n";
  }
}

bool report_replay_end(const dds::RecordedMessageStream& stream, const ReplayCounts& counts,
                       const std::string& wanted, const char* process) {
  const std::string damage = stream.damage();
  if (!damage.empty()) {
    std::cerr << process << ": " << damage << "; the " << counts.published
              << " messages before it were published\n";
  }
  if (counts.published > 0 || stream.malformed() > 0 || stream.skipped() > 0 || stop_requested()) {
    return true;
  }
  std::string seen;
  for (const std::string& topic : stream.topics_seen()) seen += (seen.empty() ? "" : ", ") + topic;
  std::cerr << process << ": " << stream.path() << " has no " << wanted << " channel"
            << (seen.empty() ? " (no channels)" : " (channels: " + seen + ")") << "\n";
  return false;
}

}  // namespace uavslam::process
