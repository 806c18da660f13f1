#include "io/SampleLog.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <map>
#include <stdexcept>

namespace uavslam::io {

namespace {

enum RecordKind : std::uint8_t { kChannelRecord = 1, kSampleRecord = 2 };

constexpr std::size_t kHeaderSize = sizeof(kSampleLogMagic) + 4;
constexpr std::size_t kRecordHeaderSize = 1 + 4;
constexpr std::size_t kSampleFieldsSize = 2 + 8 + 8;
// Larger than any sample we publish (an OctoMap snapshot is megabytes): a longer length is
// garbage, not data.
constexpr std::uint32_t kMaxBodyLength = 1u << 30;

std::string system_reason() {
  return std::strerror(errno);
}

// Little-endian encoding, independent of the host's byte order.
template <typename T>
void append(std::vector<std::uint8_t>& out, T value) {
  using U = std::make_unsigned_t<T>;
  const U bits = static_cast<U>(value);
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<std::uint8_t>(bits >> (8 * i)));
  }
}

template <typename T>
T decode(const std::uint8_t* bytes) {
  using U = std::make_unsigned_t<T>;
  U bits = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) bits |= static_cast<U>(U(bytes[i]) << (8 * i));
  return static_cast<T>(bits);
}

void append_string(std::vector<std::uint8_t>& out, const std::string& text) {
  if (text.size() > 0xFFFF) throw std::invalid_argument("channel name longer than 65535 bytes");
  append(out, static_cast<std::uint16_t>(text.size()));
  out.insert(out.end(), text.begin(), text.end());
}

// Reads the fields of a record body in order; false when the body is too short for the next one.
class BodyCursor {
 public:
  explicit BodyCursor(const std::vector<std::uint8_t>& body) : body_(body) {}
  template <typename T>
  bool read(T& value) {
    if (body_.size() - at_ < sizeof(T)) return false;
    value = decode<T>(body_.data() + at_);
    at_ += sizeof(T);
    return true;
  }
  bool read_string(std::string& text) {
    std::uint16_t length = 0;
    if (!read(length) || body_.size() - at_ < length) return false;
    text.assign(reinterpret_cast<const char*>(body_.data() + at_), length);
    at_ += length;
    return true;
  }

 private:
  const std::vector<std::uint8_t>& body_;
  std::size_t at_ = 0;
};

}  // namespace

SampleLogWriter::SampleLogWriter(const std::string& path)
    : path_(path), out_(path, std::ios::binary | std::ios::trunc) {
  if (!out_) throw file_error(path, "cannot create: " + system_reason());
  std::vector<std::uint8_t> header(kSampleLogMagic, kSampleLogMagic + sizeof(kSampleLogMagic));
  append(header, kSampleLogVersion);
  put(header.data(), header.size());
  flush();  // a reader opening the file from now on sees a valid, empty log
}

std::uint16_t SampleLogWriter::add_channel(const std::string& topic, const std::string& type) {
  for (const LogChannel& c : channels_) {
    if (c.topic == topic && c.type == type) return c.id;
  }
  if (channels_.size() > 0xFFFF) throw std::invalid_argument("more than 65536 channels");
  const auto id = static_cast<std::uint16_t>(channels_.size());
  std::vector<std::uint8_t> body;
  append(body, id);
  append_string(body, topic);
  append_string(body, type);
  std::vector<std::uint8_t> record;
  append(record, std::uint8_t{kChannelRecord});
  append(record, static_cast<std::uint32_t>(body.size()));
  record.insert(record.end(), body.begin(), body.end());
  put(record.data(), record.size());
  flush();  // rare, and its samples are meaningless without it
  channels_.push_back({id, topic, type});
  return id;
}

void SampleLogWriter::write(std::uint16_t channel, std::int64_t receive_time_ns,
                            std::int64_t source_time_ns, const std::uint8_t* payload,
                            std::size_t size) {
  if (channel >= channels_.size()) {
    throw std::invalid_argument("sample of undeclared channel " + std::to_string(channel));
  }
  if (size > kMaxBodyLength - kSampleFieldsSize) {
    throw std::invalid_argument("sample payload of " + std::to_string(size) + " bytes");
  }
  std::vector<std::uint8_t> head;
  head.reserve(kRecordHeaderSize + kSampleFieldsSize);
  append(head, std::uint8_t{kSampleRecord});
  append(head, static_cast<std::uint32_t>(kSampleFieldsSize + size));
  append(head, channel);
  append(head, receive_time_ns);
  append(head, source_time_ns);
  put(head.data(), head.size());
  put(payload, size);
}

void SampleLogWriter::flush() {
  out_.flush();
  check();
}

void SampleLogWriter::close() {
  if (!out_.is_open()) return;
  out_.close();
  check();
}

void SampleLogWriter::put(const void* data, std::size_t size) {
  out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  check();
  bytes_ += size;
}

void SampleLogWriter::check() {
  if (!out_) throw file_error(path_, "cannot write: " + system_reason());
}

SampleLogReader::SampleLogReader(const std::string& path)
    : path_(path), in_(path, std::ios::binary) {
  if (!in_) throw file_error(path, "cannot open: " + system_reason());
  char header[kHeaderSize];
  in_.read(header, sizeof(header));
  if (static_cast<std::size_t>(in_.gcount()) != sizeof(header) ||
      std::memcmp(header, kSampleLogMagic, sizeof(kSampleLogMagic)) != 0) {
    fail(0, "not a uavslam sample log (no \"UAVSLOG\" header)");
  }
  const auto version = decode<std::uint32_t>(reinterpret_cast<const std::uint8_t*>(header) +
                                             sizeof(kSampleLogMagic));
  if (version != kSampleLogVersion) {
    fail(0, "unsupported sample log version " + std::to_string(version) +
                " (this reader: " + std::to_string(kSampleLogVersion) + ")");
  }
  offset_ = kHeaderSize;
}

bool SampleLogReader::next(LogSample& sample) {
  std::uint8_t kind = 0;
  std::vector<std::uint8_t> body;
  for (;;) {
    const std::uint64_t at = offset_;
    if (!read_record(kind, body)) return false;
    if (kind == kChannelRecord) {
      add_channel(body, at);
      continue;
    }
    if (kind != kSampleRecord) continue;  // a later version's record: skip it
    BodyCursor cursor(body);
    if (!cursor.read(sample.channel) || !cursor.read(sample.receive_time_ns) ||
        !cursor.read(sample.source_time_ns)) {
      fail(at, "sample record of " + std::to_string(body.size()) + " bytes is too short");
    }
    if (!is_declared(sample.channel)) {
      fail(at, "sample of undeclared channel " + std::to_string(sample.channel));
    }
    sample.payload.assign(body.begin() + kSampleFieldsSize, body.end());
    return true;
  }
}

const LogChannel& SampleLogReader::channel(std::uint16_t id) const {
  for (const LogChannel& c : channels_) {
    if (c.id == id) return c;
  }
  throw std::out_of_range("channel " + std::to_string(id) + " is not declared in " + path_);
}

void SampleLogReader::fail(std::uint64_t at, const std::string& problem) const {
  throw file_error(path_, "byte " + std::to_string(at) + ": " + problem);
}

bool SampleLogReader::read_record(std::uint8_t& kind, std::vector<std::uint8_t>& body) {
  const std::uint64_t at = offset_;
  std::uint8_t head[kRecordHeaderSize];
  in_.read(reinterpret_cast<char*>(head), sizeof(head));
  const auto got = static_cast<std::size_t>(in_.gcount());
  if (got == 0) return false;
  if (got < sizeof(head)) {
    fail(at, "truncated record header (" + std::to_string(got) + " of " +
                 std::to_string(sizeof(head)) + " bytes)");
  }
  kind = head[0];
  const auto length = decode<std::uint32_t>(head + 1);
  if (kind == 0 || length > kMaxBodyLength) {
    fail(at, "corrupt record (kind " + std::to_string(kind) + ", length " + std::to_string(length) +
                 ")");
  }
  // A garbage length must not allocate a gigabyte: above a megabyte, look at what is left first.
  if (length > (1u << 20) && length > bytes_left()) {
    fail(at, "truncated record (" + std::to_string(bytes_left()) + " of " + std::to_string(length) +
                 " body bytes)");
  }
  body.resize(length);
  in_.read(reinterpret_cast<char*>(body.data()), static_cast<std::streamsize>(length));
  const auto body_got = static_cast<std::size_t>(in_.gcount());
  if (body_got < length) {
    fail(at, "truncated record (" + std::to_string(body_got) + " of " + std::to_string(length) +
                 " body bytes)");
  }
  offset_ = at + sizeof(head) + length;
  return true;
}

std::uint64_t SampleLogReader::bytes_left() {
  const auto here = in_.tellg();
  in_.seekg(0, std::ios::end);
  const auto end = in_.tellg();
  in_.seekg(here);
  return end > here ? static_cast<std::uint64_t>(end - here) : 0;
}

void SampleLogReader::add_channel(const std::vector<std::uint8_t>& body, std::uint64_t at) {
  LogChannel channel;
  BodyCursor cursor(body);
  if (!cursor.read(channel.id) || !cursor.read_string(channel.topic) ||
      !cursor.read_string(channel.type)) {
    fail(at, "channel record of " + std::to_string(body.size()) + " bytes is malformed");
  }
  if (is_declared(channel.id))
    fail(at, "channel " + std::to_string(channel.id) + " declared twice");
  channels_.push_back(std::move(channel));
}

bool SampleLogReader::is_declared(std::uint16_t id) const {
  return std::any_of(channels_.begin(), channels_.end(),
                     [id](const LogChannel& c) { return c.id == id; });
}

SampleLog read_sample_log(const std::string& path) {
  SampleLogReader reader(path);
  SampleLog log;
  LogSample sample;
  while (reader.next(sample)) log.samples.push_back(std::move(sample));
  log.channels = reader.channels();
  return log;
}

SampleLog recover_sample_log(const std::string& path) {
  SampleLogReader reader(path);
  SampleLog log;
  LogSample sample;
  try {
    while (reader.next(sample)) log.samples.push_back(std::move(sample));
  } catch (const FileError& e) {
    log.damage = e.what();
  }
  log.channels = reader.channels();
  return log;
}

std::vector<ChannelSummary> summarize(const SampleLog& log) {
  std::map<std::uint16_t, ChannelSummary> by_id;
  for (const LogChannel& c : log.channels) by_id[c.id].channel = c;
  for (const LogSample& s : log.samples) {
    ChannelSummary& summary = by_id[s.channel];
    if (summary.samples == 0) {
      summary.first_receive_ns = s.receive_time_ns;
      summary.last_receive_ns = s.receive_time_ns;
    }
    summary.first_receive_ns = std::min(summary.first_receive_ns, s.receive_time_ns);
    summary.last_receive_ns = std::max(summary.last_receive_ns, s.receive_time_ns);
    ++summary.samples;
    summary.payload_bytes += s.payload.size();
  }
  std::vector<ChannelSummary> out;
  for (auto& entry : by_id) out.push_back(std::move(entry.second));
  return out;
}

}  // namespace uavslam::io
