// The readers under fuzzing take a path, as the tools do: each input becomes an in-memory file
// (memfd) reached through /proc/self/fd, so a run touches no disk.
#pragma once

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace uavslam::fuzz {

class FuzzInputFile {
 public:
  FuzzInputFile() : fd_(memfd_create("uavslam_fuzz", 0)) {}
  ~FuzzInputFile() { close(fd_); }
  FuzzInputFile(const FuzzInputFile&) = delete;
  FuzzInputFile& operator=(const FuzzInputFile&) = delete;

  // Replaces the file's contents with the input and returns its path.
  std::string hold(const std::uint8_t* data, std::size_t size) {
    if (ftruncate(fd_, 0) != 0) return path();
    std::size_t written = 0;
    while (written < size) {
      const ssize_t n = pwrite(fd_, data + written, size - written, off_t(written));
      if (n <= 0) break;
      written += std::size_t(n);
    }
    return path();
  }
  std::string path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_;
};

}  // namespace uavslam::fuzz
