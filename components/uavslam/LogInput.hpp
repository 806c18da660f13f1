// A flight's sensor data as the pipeline takes it, in time order, one event at a time, whatever
// it was read from: a CARMEN log (streamed, however large), a simulated flight, or an MCAP
// recording (streamed too). The offline mapper reads its input twice (real-time pass, dense pass),
// so an input is opened anew for each pass.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/Types.hpp"
#include "io/NoReturnCode.hpp"

namespace uavslam::cli {

struct LogEvent {
  enum class Kind { Imu, Odometry, Velocity, Scan };
  explicit LogEvent(Kind k) : kind(k) {}

  Kind kind;
  ImuSample imu;
  OdometrySample odometry;
  VelocitySample velocity;
  Scan scan;
  double output_stamp = 0.0;       // the scan's own stamp for outputs (CARMEN: ipc_timestamp)
  std::optional<Pose> truth;       // the true body pose at the scan, when the input knows it
  std::optional<Vec3> start_hint;  // where the body is at this scan, to start the map there
};

class LogInput {
 public:
  virtual ~LogInput() = default;
  // The next event; nullopt at the end.
  virtual std::optional<LogEvent> next() = 0;
  // Scans the input holds (for progress), 0 when unknown.
  virtual std::size_t expected_scans() const = 0;
  // Records skipped as malformed so far, and their descriptions since the last call.
  virtual std::size_t malformed() const { return 0; }
  virtual std::vector<std::string> take_problems() { return {}; }
  // Seconds of data so far (last stamp - first stamp).
  virtual double data_seconds() const = 0;
  // Why the input ended before the end of its file (a recording cut short: where and why), ""
  // when it did not. Known once next() returned nullopt.
  virtual std::string damage() const { return ""; }
  // The range the log writes for "no return", when the input had to learn it (CARMEN FLASER).
  virtual std::optional<io::NoReturnCode> no_return_code() const { return std::nullopt; }
};

using LogInputFactory = std::function<std::unique_ptr<LogInput>()>;

// A robustness probe (data README): each scan's odometry heading moved by a pseudo-random amount,
// uniform in +-amplitude rad, reproducible from the seed. A matcher whose result changes a lot
// under 1e-6 rad is chaotic, and one run's figure says little about it.
struct HeadingJitter {
  double amplitude = 0.0;
  unsigned seed = 1;
};

// Scans of a CARMEN log in file order on its monotonic timeline (io/CarmenTimeline); each scan
// brings the robot's odometry heading as the orientation (an IMU sample) and its odometry
// position, before the scan itself. Throws io::FileError when the file cannot be opened.
std::unique_ptr<LogInput> open_carmen_input(const std::string& path, HeadingJitter jitter = {});

// The `scan`, `imu` and (when there) `velocity` and `ground_truth` channels of an MCAP recording
// (the convention of dds/McapChannels.hpp; with a vehicle prefix, "uav1/scan", when the file has
// only that vehicle's or `vehicle` names it) in log-time order: IMU samples and scans as the
// pipeline takes them, each scan with the true pose recorded at its stamp as its truth and start.
// `geometry`: the sensor's (mount, mirror); null: each scan's beam layout as a planar scanner at
// the body origin (dds::MessageScanGeometry). A file cut short is read up to its damage (damage()
// says where). io::FileError naming the file when it cannot be opened, is not MCAP, holds no whole
// message, or has scans but no IMU channel (nothing to orient them), or several vehicles' scans and
// no `vehicle` to choose.
std::unique_ptr<LogInput> open_mcap_input(const std::string& path,
                                          std::shared_ptr<const ScanGeometry> geometry,
                                          const std::string& vehicle = "");

struct SensorLog;
// A flight simulated beforehand (simulate_sensors), with its ground truth; the passes share it.
std::unique_ptr<LogInput> open_simulated_input(std::shared_ptr<const SensorLog> log);

}  // namespace uavslam::cli
