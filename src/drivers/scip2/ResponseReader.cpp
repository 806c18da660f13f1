#include "drivers/scip2/ResponseReader.hpp"

#include "drivers/scip2/Encoding.hpp"

namespace uavslam::drivers::scip2 {
namespace {

// A data line holds at most 64 characters + checksum (section 8, MD/GD: "Data Block (64 byte)");
// VV/PP/II lines are longer text. Anything longer is not SCIP.
constexpr std::size_t kMaxLine = 256;
// Echoes: 2-letter command + at most 13 parameter characters + ';' + 16-character string
// (section 7); "SCIP2.0" (section 2).
constexpr std::size_t kMaxEcho = 40;
// The largest reply: ME over the full 1440-step circle, 6 characters per step, 64 per line.
constexpr std::size_t kMaxResponseBytes = 32 * 1024;

bool is_printable(char c) {
  return c >= 0x20 && c <= 0x7E;
}

bool is_upper(char c) {
  return c >= 'A' && c <= 'Z';
}

bool looks_like_echo(const std::string& line) {
  if (line.size() < 2 || line.size() > kMaxEcho) return false;
  if (!is_upper(line[0]) || !is_upper(line[1])) return false;
  for (const char c : line) {
    if (!is_printable(c)) return false;
  }
  return true;
}

// Section 7: status = 2 characters + their checksum. Section 2: the SCIP2.0 command answers a
// bare "0" (switched) or "E" (not supported).
bool is_status_line(const std::string& echo, const std::string& line) {
  if (echo == "SCIP2.0" && (line == "0" || line == "E")) return true;
  return line.size() == 3 && is_printable(line[0]) && is_printable(line[1]) &&
         has_valid_checksum(line);
}

// The content of a data line without its checksum, or false when the checksum is wrong. Section
// 8 (VV, PP, II): text lines end with ';' + the checksum of the text before the ';'.
bool strip_checksum(const std::string& line, std::string& content) {
  if (has_valid_checksum(line)) {
    content = line.substr(0, line.size() - 1);
    return true;
  }
  const std::size_t n = line.size();
  if (n >= 3 && line[n - 2] == ';' &&
      checksum(std::string_view(line).substr(0, n - 2)) == line[n - 1]) {
    content = line.substr(0, n - 2);
    return true;
  }
  return false;
}

}  // namespace

void ResponseReader::feed(std::string_view bytes, std::vector<Response>& out) {
  for (const char c : bytes) {
    if (c == '\n') {
      if (skipping_long_line_) {
        skipping_long_line_ = false;
        ++counts_.garbage_bytes;
        continue;
      }
      end_line(out);
      continue;
    }
    if (skipping_long_line_) {
      ++counts_.garbage_bytes;
      continue;
    }
    line_.push_back(c);
    if (line_.size() > kMaxLine) {
      counts_.garbage_bytes += line_.size();
      line_.clear();
      discard_response();
      skipping_long_line_ = true;
    }
  }
}

void ResponseReader::reset() {
  line_.clear();
  skipping_long_line_ = false;
  expect_ = Expect::Echo;
  response_ = Response{};
  response_bytes_ = 0;
}

void ResponseReader::end_line(std::vector<Response>& out) {
  const std::string line = std::move(line_);
  line_.clear();
  response_bytes_ += line.size() + 1;
  switch (expect_) {
    case Expect::Echo:
      take_echo_line(line);
      break;
    case Expect::Status:
      take_status_line(line);
      break;
    case Expect::Data:
      take_data_line(line, out);
      break;
  }
  if (expect_ != Expect::Echo && response_bytes_ > kMaxResponseBytes) discard_response();
}

void ResponseReader::take_echo_line(const std::string& line) {
  if (!looks_like_echo(line)) {
    counts_.garbage_bytes += line.size() + 1;
    response_bytes_ = 0;
    return;
  }
  response_ = Response{};
  response_.echo = line;
  response_bytes_ = line.size() + 1;
  expect_ = Expect::Status;
}

void ResponseReader::take_status_line(const std::string& line) {
  if (!is_status_line(response_.echo, line)) {
    // The "echo" was garbage that happened to look like one; this line may be the real echo.
    counts_.garbage_bytes += response_.echo.size() + 1;
    expect_ = Expect::Echo;
    take_echo_line(line);
    return;
  }
  response_.status = line.size() == 3 ? line.substr(0, 2) : line;
  expect_ = Expect::Data;
}

void ResponseReader::take_data_line(const std::string& line, std::vector<Response>& out) {
  if (line.empty()) {
    ++counts_.responses;
    out.push_back(std::move(response_));
    response_ = Response{};
    response_bytes_ = 0;
    expect_ = Expect::Echo;
    return;
  }
  std::string content;
  if (strip_checksum(line, content)) {
    response_.data.push_back(std::move(content));
    return;
  }
  ++counts_.checksum_errors;
  if (looks_like_echo(line)) {
    // Possibly the next response's echo after a reply that was cut short: deliver the damaged
    // one and try this line as a new echo (its status line decides).
    response_.intact = false;
    ++counts_.responses;
    ++counts_.cut_short;
    out.push_back(std::move(response_));
    expect_ = Expect::Echo;
    take_echo_line(line);
    return;
  }
  response_.intact = false;
  response_.data.push_back(line);
}

void ResponseReader::discard_response() {
  if (expect_ != Expect::Echo) counts_.garbage_bytes += response_bytes_;
  response_ = Response{};
  response_bytes_ = 0;
  expect_ = Expect::Echo;
}

}  // namespace uavslam::drivers::scip2
