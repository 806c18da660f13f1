#include "io/OutputFile.hpp"

#include <cerrno>
#include <cstring>

namespace uavslam::io {

OutputFile::OutputFile(const std::string& path, const char* mode)
    : path_(path), file_(std::fopen(path.c_str(), mode)) {
  if (!file_) throw file_error(path, std::string("cannot write: ") + std::strerror(errno));
}

void OutputFile::write(const void* data, std::size_t size) {
  if (size == 0) return;  // data may be null for an empty buffer
  if (std::fwrite(data, 1, size, file_.get()) != size) {
    throw file_error(path_, std::string("cannot write: ") + std::strerror(errno));
  }
}

void OutputFile::close() {
  if (!file_) return;
  const bool write_failed = std::ferror(file_.get()) != 0;
  const int close_result = std::fclose(file_.release());
  if (write_failed || close_result != 0) {
    throw file_error(path_, std::string("cannot write: ") + std::strerror(errno));
  }
}

}  // namespace uavslam::io
