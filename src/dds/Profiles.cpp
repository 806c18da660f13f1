#include "dds/Profiles.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/log/Log.hpp>

#include "dds/DdsError.hpp"

#ifndef UAVSLAM_QOS_DIR
#error "UAVSLAM_QOS_DIR must be defined (src/dds/CMakeLists.txt sets it)"
#endif

namespace uavslam::dds {

namespace {

using eprosima::fastdds::dds::DomainParticipantFactory;
using eprosima::fastdds::dds::Log;
using eprosima::fastrtps::types::ReturnCode_t;

// Fast DDS explains why it rejects an XML file only in its (asynchronous) log. This consumer,
// registered once beside the default one, keeps the XML parser's messages while a load is under
// way so the DdsError can quote them. It holds no state of its own: if someone clears Fast DDS's
// consumers, the reason is merely less precise.
struct ParserLogCapture {
  std::mutex mutex;
  bool active = false;
  std::vector<std::string> messages;
};

ParserLogCapture& capture() {
  static ParserLogCapture instance;
  return instance;
}

class ParserLogConsumer : public eprosima::fastdds::dds::LogConsumer {
 public:
  void Consume(const Log::Entry& entry) override {
    if (entry.kind != Log::Kind::Error) return;
    const std::string category = entry.context.category ? entry.context.category : "";
    if (category.find("XMLPARSER") == std::string::npos) return;
    ParserLogCapture& c = capture();
    std::lock_guard<std::mutex> lock(c.mutex);
    if (c.active && c.messages.size() < 8) c.messages.push_back(entry.message);
  }
};

// Serialises loads; the set of paths already loaded (as given and canonical).
std::mutex& load_mutex() {
  static std::mutex m;
  return m;
}

std::set<std::string>& loaded_paths() {
  static std::set<std::string> paths;
  return paths;
}

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
  throw DdsError("cannot load QoS profiles from '" + path + "': " + reason);
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (const std::string& part : parts) {
    if (!out.empty()) out += separator;
    out += part;
  }
  return out;
}

}  // namespace

void load_profiles(const std::string& xml_path) {
  std::lock_guard<std::mutex> lock(load_mutex());

  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path path(xml_path);
  if (xml_path.empty()) fail(xml_path, "empty path");
  if (!fs::exists(path, ec)) fail(xml_path, "no such file");
  if (!fs::is_regular_file(path, ec)) fail(xml_path, "not a regular file");
  const std::string canonical = fs::canonical(path, ec).string();
  if (loaded_paths().count(canonical) != 0) return;
  {
    std::ifstream in(path);
    if (!in) fail(xml_path, "cannot open it for reading");
  }

  static std::once_flag consumer_registered;
  std::call_once(consumer_registered, [] {
    Log::RegisterConsumer(
        std::unique_ptr<eprosima::fastdds::dds::LogConsumer>(new ParserLogConsumer()));
  });

  ParserLogCapture& c = capture();
  {
    std::lock_guard<std::mutex> capture_lock(c.mutex);
    c.messages.clear();
    c.active = true;
  }
  const ReturnCode_t result =
      DomainParticipantFactory::get_instance()->load_XML_profiles_file(canonical);
  if (result != ReturnCode_t::RETCODE_OK) {
    Log::Flush();  // the parser's messages reach the consumer on Fast DDS's logging thread
    std::vector<std::string> messages;
    {
      std::lock_guard<std::mutex> capture_lock(c.mutex);
      c.active = false;
      messages.swap(c.messages);
    }
    fail(xml_path, messages.empty() ? "Fast DDS rejected the XML (see its log above)"
                                    : "Fast DDS rejected the XML: " + join(messages, "; "));
  }
  {
    std::lock_guard<std::mutex> capture_lock(c.mutex);
    c.active = false;
    c.messages.clear();
  }
  loaded_paths().insert(canonical);
}

// An installed tree (cmake --install: bin/, qos/, config/) keeps the profiles beside the
// executables' directory; a build tree uses the source's qos/.
std::string default_profiles_path() {
  const char* file = std::getenv("UAVSLAM_QOS_FILE");
  if (file != nullptr && *file != '\0') return file;
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path installed =
        exe.parent_path().parent_path() / "qos" / "uavslam_profiles.xml";
    if (std::filesystem::exists(installed, error)) return installed.string();
  }
  return UAVSLAM_QOS_DIR "/uavslam_profiles.xml";
}

std::vector<std::string> profile_names(const std::string& xml_path, const std::string& element) {
  std::ifstream in(xml_path);
  if (!in) return {};
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::regex pattern("<" + element + "\\b[^>]*\\bprofile_name\\s*=\\s*\"([^\"]*)\"");
  std::vector<std::string> names;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), pattern);
       it != std::sregex_iterator(); ++it) {
    names.push_back((*it)[1].str());
  }
  return names;
}

}  // namespace uavslam::dds
