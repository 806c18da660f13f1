// The one exception the file readers and writers of io throw: a file that cannot be opened,
// written or parsed. The message names the file (and the line, when one is to blame) so that it
// can be shown to the user as is.
#pragma once

#include <stdexcept>
#include <string>

namespace uavslam::io {

class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "<path>: <what>", e.g. "est.tum: cannot open: No such file or directory".
inline FileError file_error(const std::string& path, const std::string& what) {
  return FileError(path + ": " + what);
}

// "<path>:<line>: <what>", the compiler-style location editors can jump to.
inline FileError line_error(const std::string& path, std::size_t line, const std::string& what) {
  return FileError(path + ":" + std::to_string(line) + ": " + what);
}

}  // namespace uavslam::io
