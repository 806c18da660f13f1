#include "drivers/scip2/ReplyText.hpp"

#include "drivers/scip2/Encoding.hpp"

namespace uavslam::drivers::scip2 {

std::string reply_text(const std::string& echo, const std::string& status,
                       const std::vector<std::string>& lines) {
  std::string text = echo + "\n" + status;
  if (status.size() == 2) text += checksum(status);
  text += "\n";
  for (const std::string& line : lines) text += line + "\n";
  return text + "\n";
}

std::string info_line(const std::string& key, const std::string& value) {
  const std::string text = key + ":" + value;
  return text + ";" + checksum(text);
}

}  // namespace uavslam::drivers::scip2
