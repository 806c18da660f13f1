#include "EmulatedHokuyo.hpp"

#include <cmath>

#include "drivers/scip2/Encoding.hpp"
#include "drivers/scip2/ReplyText.hpp"
#include "drivers/scip2/ScanReply.hpp"

namespace uavslam::test {
namespace {

using drivers::scip2::info_line;
using drivers::scip2::reply_text;

constexpr double kPeriod = 0.025;  // SCAN 2400 rpm
constexpr std::uint32_t kMinMm = 23;
constexpr std::uint32_t kMaxMm = 60000;
constexpr std::uint32_t kNoReturn = 1;  // an error code below DMIN, as the UTM-30LX sends

std::uint32_t to_mm(float range) {
  if (!std::isfinite(range)) return kNoReturn;
  const double mm = std::round(static_cast<double>(range) * 1000.0);
  if (mm > kMaxMm) return kNoReturn;
  return static_cast<std::uint32_t>(std::max(0.0, mm));
}

}  // namespace

EmulatedHokuyo::EmulatedHokuyo(EmulatorOptions options, std::vector<std::vector<float>> scans,
                               double boot_time)
    : options_(options), scans_(std::move(scans)), boot_time_(boot_time) {}

int EmulatedHokuyo::beams() const {
  return scans_.empty() ? 0 : static_cast<int>(scans_.front().size());
}

std::uint32_t EmulatedHokuyo::sensor_ms(double host) const {
  const double ms =
      (host - boot_time_) * 1e3 * (1.0 + options_.drift_ppm * 1e-6) + options_.offset_ms;
  return static_cast<std::uint32_t>(static_cast<std::int64_t>(std::floor(ms)) & 0xFFFFFF);
}

void EmulatedHokuyo::reset_link() {
  streaming_ = false;
  pending_.clear();
}

std::string EmulatedHokuyo::receive(const std::string& bytes, double now) {
  std::string out;
  for (const char c : bytes) {
    if (c == '\n' || c == '\r') {
      if (!pending_.empty()) out += answer(pending_, now);
      pending_.clear();
    } else if (pending_.size() < 64) {
      pending_.push_back(c);
    }
  }
  return out;
}

std::string EmulatedHokuyo::answer(const std::string& command, double now) {
  if (command == "SCIP2.0") return reply_text(command, "0");
  if (command == "VV") {
    return reply_text(
        command, "00",
        {info_line("VEND", "uavslam test"), info_line("PROD", "scip2_emulator"),
         info_line("FIRM", "1.0"), info_line("PROT", "SCIP 2.0"), info_line("SERI", "EMU00001")});
  }
  if (command == "PP") {
    return reply_text(command, "00",
                      {info_line("MODL", "UTM-30LX"), info_line("DMIN", std::to_string(kMinMm)),
                       info_line("DMAX", std::to_string(kMaxMm)), info_line("ARES", "1440"),
                       info_line("AMIN", "0"), info_line("AMAX", std::to_string(beams() - 1)),
                       info_line("AFRT", "540"), info_line("SCAN", "2400")});
  }
  if (command == "II") {
    return reply_text(command, "00",
                      {info_line("MODL", "UTM-30LX"), info_line("LASR", streaming_ ? "ON" : "OFF"),
                       info_line("SCSP", "2400"), info_line("STAT", "Stable 000 no error.")});
  }
  if (command == "TM0" || command == "TM2" || command == "BM") return reply_text(command, "00");
  if (command == "TM1") {
    const std::string stamp = drivers::scip2::encode(sensor_ms(now), 4);
    return reply_text(command, "00", {stamp + drivers::scip2::checksum(stamp)});
  }
  if (command == "QT" || command == "RS") {
    streaming_ = false;
    return reply_text(command, "00");
  }
  const auto request = drivers::scip2::parse_scan_echo(command);
  if (request && request->continuous && (options_.intensity || !request->with_intensity) &&
      request->first_step == 0 && request->last_step == beams() - 1 && request->cluster == 1) {
    streaming_ = true;
    stream_echo_ = command;
    stream_start_ = now;
    stream_next_ = 0;
    return reply_text(command, "00");
  }
  return reply_text(command, "0E");  // section 9: a command this sensor does not take
}

double EmulatedHokuyo::next_due() const {
  if (!streaming_) return 1e300;
  return stream_start_ + static_cast<double>(stream_next_ + 1) * kPeriod;
}

std::string EmulatedHokuyo::due_scans(double now,
                                      const std::function<void(const SentScan&)>& sent) {
  std::string out;
  std::uniform_real_distribution<double> jitter(0.0, options_.jitter_ms * 1e-3);
  while (streaming_ && now >= next_due() + jitter(random_)) {
    SentScan scan;
    scan.index = next_index_++;
    scan.true_time = stream_start_ + static_cast<double>(stream_next_) * kPeriod;
    scan.stamp_ms = sensor_ms(scan.true_time);
    scan.sim_scan = scan.index % scans_.size();
    ++stream_next_;
    const std::uint64_t n = scan.index + 1;
    if (options_.garbage_every > 0 && n % static_cast<std::uint64_t>(options_.garbage_every) == 0) {
      out += "\x07\xfe garbage \x01\n\n";
    }
    std::string reply = scan_reply(scan);
    if (options_.truncate_every > 0 &&
        n % static_cast<std::uint64_t>(options_.truncate_every) == 0) {
      reply.resize(reply.size() / 2);
    }
    out += reply;
    sent(scan);
  }
  return out;
}

std::string EmulatedHokuyo::scan_reply(const SentScan& sent) {
  drivers::scip2::ScanData scan;
  scan.timestamp_ms = sent.stamp_ms;
  for (const float r : scans_[sent.sim_scan]) {
    scan.distances_mm.push_back(to_mm(r));
    if (stream_echo_[1] == 'E') scan.intensities.push_back(std::isfinite(r) ? 3000 : 0);
  }
  std::vector<std::string> lines = drivers::scip2::encode_scan_lines(scan);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    ++blocks_sent_;
    if (options_.bad_checksum_every > 0 &&
        blocks_sent_ % static_cast<std::uint64_t>(options_.bad_checksum_every) == 0) {
      lines[i].back() = static_cast<char>(lines[i].back() == '0' ? '1' : '0');
    }
  }
  return reply_text(stream_echo_, "99", lines);
}

}  // namespace uavslam::test
