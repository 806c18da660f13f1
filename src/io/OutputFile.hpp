// A file being written, for the writers of io: opened in the constructor, and closed by close(),
// which reports what the C library only tells at the end (a full disk shows up when the buffer is
// flushed). Every error is a FileError naming the path and the system's reason.
#pragma once

#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>

#include "io/FileError.hpp"

namespace uavslam::io {

class OutputFile {
 public:
  // mode: "wb" or "w" as for fopen.
  OutputFile(const std::string& path, const char* mode = "wb");

  void write(const void* data, std::size_t size);
  void write(const std::string& text) { write(text.data(), text.size()); }
  // The stream, for fprintf-style writers; errors on it are reported by close().
  std::FILE* stream() { return file_.get(); }
  // Flushes and closes; throws FileError if anything written did not reach the file.
  void close();

 private:
  struct Closer {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  std::string path_;
  std::unique_ptr<std::FILE, Closer> file_;
};

}  // namespace uavslam::io
