#include "common/RunNode.hpp"

#include <iostream>
#include <stdexcept>

#include "dds/DdsError.hpp"
#include "io/FileError.hpp"
#include "io/YamlReader.hpp"

namespace uavslam::process {

std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return std::nullopt;
}

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
