// libFuzzer target: both MCAP readers (src/io/McapReader). Any input must give the complete
// messages before the damage and a report, never a crash, undefined behaviour or an allocation
// larger than the file (for an lz4 or zstd chunk: than what its data really decompresses to, at
// most 256 MiB). The seeds in test/fuzz/corpus/mcap are one file uncompressed, lz4 and zstd.
#include <cstddef>
#include <cstdint>

#include "FuzzInputFile.hpp"
#include "io/McapReader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static uavslam::fuzz::FuzzInputFile file;
  const std::string path = file.hold(data, size);
  std::size_t streamed = 0;
  {
    uavslam::io::McapStreamReader reader(path);
    uavslam::io::mcap::Message message;
    while (reader.next(message)) ++streamed;
  }
  uavslam::io::McapIndexedReader indexed(path);
  std::size_t seen = 0;
  indexed.read_messages(0, [&](const uavslam::io::mcap::Message&) { return ++seen < 100000; });
  return 0;
}
