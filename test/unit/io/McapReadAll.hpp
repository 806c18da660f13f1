// Every message of an MCAP file as each reader returns it, with the reader's report, and the
// comparisons the tests of the readers make of them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "io/Mcap.hpp"
#include "io/McapReader.hpp"

namespace uavslam::test {

inline std::vector<io::mcap::Message> stream_all(const std::string& path,
                                                 io::McapReadReport* report = nullptr) {
  io::McapStreamReader reader(path);
  std::vector<io::mcap::Message> messages;
  io::mcap::Message message;
  while (reader.next(message)) messages.push_back(message);
  if (report) *report = reader.report();
  return messages;
}

inline std::vector<io::mcap::Message> indexed_from(const std::string& path,
                                                   std::uint64_t start_time,
                                                   io::McapReadReport* report = nullptr) {
  io::McapIndexedReader reader(path);
  std::vector<io::mcap::Message> messages;
  const io::McapReadReport result =
      reader.read_messages(start_time, [&](const io::mcap::Message& m) {
        messages.push_back(m);
        return true;
      });
  if (report) *report = result;
  return messages;
}

inline bool same(const io::mcap::Message& a, const io::mcap::Message& b) {
  return a.channel_id == b.channel_id && a.sequence == b.sequence && a.log_time == b.log_time &&
         a.publish_time == b.publish_time && a.data == b.data;
}

// True when every message of `got` is one of `all`, in the same order: nothing made up.
inline bool is_subsequence(const std::vector<io::mcap::Message>& got,
                           const std::vector<io::mcap::Message>& all) {
  auto next = all.begin();
  for (const io::mcap::Message& m : got) {
    next = std::find_if(next, all.end(), [&](const io::mcap::Message& a) { return same(a, m); });
    if (next == all.end()) return false;
    ++next;
  }
  return true;
}

}  // namespace uavslam::test
