// The protocol side of scip2_emulator: a UTM-30LX-like sensor that answers SCIP 2.0 commands
// (C-42-03320B sections 2 and 8: SCIP2.0, VV, PP, II, TM0/1/2, BM, QT, RS, MD, ME) and, while a
// stream runs, sends one scan every 25 ms from a list of simulated scans. Its clock runs at
// (1 + drift) times host time from an offset; each scan is stamped at its sweep's start and sent
// after the sweep (plus a random delay). Faults: a wrong checksum every N data blocks, garbage
// before every Nth scan, every Nth scan cut off mid-line.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace uavslam::test {

struct EmulatorOptions {
  double drift_ppm = 0.0;
  double offset_ms = 0.0;      // the sensor clock when the emulator starts
  double jitter_ms = 0.0;      // extra send delay, uniform in [0, jitter]
  int bad_checksum_every = 0;  // data blocks; 0: never
  int garbage_every = 0;       // scans
  int truncate_every = 0;      // scans
  bool intensity = true;       // false: ME is refused (status 0E), as MD-only models do
};

// One scan sent: for the test to compare with what the driver published.
struct SentScan {
  std::uint64_t index = 0;     // 0, 1, ... over the emulator's life
  double true_time = 0.0;      // host system clock (s) at the sweep's start
  std::uint32_t stamp_ms = 0;  // the sensor clock then, as sent
  std::size_t sim_scan = 0;    // which of the simulated scans
};

class EmulatedHokuyo {
 public:
  EmulatedHokuyo(EmulatorOptions options, std::vector<std::vector<float>> scans, double boot_time);

  // The reply bytes to the command bytes `bytes` (LF/CR-terminated lines), at host time `now`.
  std::string receive(const std::string& bytes, double now);
  // The scans due by `now` (empty while not streaming); `sent` is told about each.
  std::string due_scans(double now, const std::function<void(const SentScan&)>& sent);
  // When the next scan is due (host s), or a large value while not streaming.
  double next_due() const;
  // A disconnect or a new client: the stream stops, partial commands are forgotten.
  void reset_link();

  int beams() const;

 private:
  std::string answer(const std::string& command, double now);
  std::string scan_reply(const SentScan& scan);
  std::uint32_t sensor_ms(double host) const;

  EmulatorOptions options_;
  std::vector<std::vector<float>> scans_;
  double boot_time_;
  std::string pending_;
  bool streaming_ = false;
  std::string stream_echo_;
  double stream_start_ = 0.0;
  std::uint64_t stream_next_ = 0;
  std::uint64_t next_index_ = 0;
  std::uint64_t blocks_sent_ = 0;
  std::mt19937 random_{42};
};

}  // namespace uavslam::test
