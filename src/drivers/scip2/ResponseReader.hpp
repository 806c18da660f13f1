// Frames the bytes a SCIP 2.0 sensor sends into responses (C-42-03320B section 7, "Communication
// Format"): the echo of the command (no checksum), a status line (2 characters + checksum), data
// lines each ending with a checksum, and an empty line (the second of two LFs) ending the reply.
// Bytes that cannot start a response are counted as garbage and skipped up to the next LF, a data
// line with a wrong checksum marks its response damaged, and a damaged line that is followed by a
// valid status line starts a new response (the previous one was cut short): the stream
// resynchronises by itself. The reader keeps at most one partial line and one partial response.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace uavslam::drivers::scip2 {

struct Response {
  std::string echo;               // the command line as the sensor echoed it
  std::string status;             // "00", "99", an error code; "0"/"E" for the SCIP2.0 command
  std::vector<std::string> data;  // the lines after the status, checksums removed
  bool intact = true;             // false: a line failed its checksum or the reply was cut short
};

struct ReaderCounts {
  std::uint64_t responses = 0;        // complete responses framed (damaged ones included)
  std::uint64_t garbage_bytes = 0;    // bytes skipped outside any response
  std::uint64_t checksum_errors = 0;  // lines whose checksum character did not match
  std::uint64_t cut_short = 0;        // responses a new response interrupted
};

class ResponseReader {
 public:
  // Frames `bytes` (split anywhere); each response completed by them is appended to `out`.
  void feed(std::string_view bytes, std::vector<Response>& out);
  // Forgets the partial line and response (after a reconnect).
  void reset();

  const ReaderCounts& counts() const { return counts_; }

 private:
  enum class Expect { Echo, Status, Data };

  void end_line(std::vector<Response>& out);
  void take_echo_line(const std::string& line);
  void take_status_line(const std::string& line);
  void take_data_line(const std::string& line, std::vector<Response>& out);
  void discard_response();

  Expect expect_ = Expect::Echo;
  std::string line_;
  bool skipping_long_line_ = false;
  Response response_;
  std::size_t response_bytes_ = 0;
  ReaderCounts counts_;
};

}  // namespace uavslam::drivers::scip2
