#include "common/RunNode.hpp"

#include <iostream>
#include <stdexcept>

#include "dds/DdsError.hpp"
#include "io/FileError.hpp"
#include "io/YamlReader.hpp"

namespace uavslam::process {

int run_node(const char* name, const std::function<int()>& body) {
  try {
    return body();
  } catch (const io::ConfigError& e) {
    std::cerr << name << ": " << e.what() << "\n";
  } catch (const io::FileError& e) {
    std::cerr << name << ": " << e.what() << "\n";
  } catch (const dds::DdsError& e) {
    std::cerr << name << ": " << e.what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << name << ": " << e.what() << "\n";
    return 1;
  }
  return 2;
}

}  // namespace uavslam::process
