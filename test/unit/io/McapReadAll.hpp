// Every message of an MCAP file as each reader returns it, with the reader's report: the tests
// of the readers compare these.
#pragma once

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

}  // namespace uavslam::test
