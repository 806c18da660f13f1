// The one exception the DDS layer throws: a profile file that does not load, a profile name it
// does not define, an entity Fast DDS refuses to create. The message names the file and profile.
#pragma once

#include <stdexcept>
#include <string>

namespace uavslam::dds {

class DdsError : public std::runtime_error {
 public:
  explicit DdsError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace uavslam::dds
