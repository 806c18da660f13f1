#include "LogInput.hpp"

#include <algorithm>
#include <deque>
#include <fstream>
#include <limits>
#include <random>

#include "SimulatedFlight.hpp"
#include "core/Heading.hpp"
#include "io/CarmenScanStream.hpp"
#include "io/FileError.hpp"

namespace uavslam::cli {
namespace {

// Counting a log's scan lines costs a quick read; the progress bar then shows the time left.
std::size_t count_carmen_scans(const std::string& path) {
  std::ifstream in(path);
  std::size_t scans = 0;
  for (std::string line; std::getline(in, line);) {
    scans += line.rfind("FLASER ", 0) == 0 || line.rfind("ROBOTLASER1 ", 0) == 0;
  }
  return scans;
}

class StampRange {
 public:
  void add(double t) {
    first_ = std::min(first_, t);
    last_ = std::max(last_, t);
  }
  double seconds() const { return last_ > first_ ? last_ - first_ : 0.0; }

 private:
  double first_ = std::numeric_limits<double>::infinity();
  double last_ = -std::numeric_limits<double>::infinity();
};

// One geometry per distinct beam layout and laser mount (a log normally has one).
class CarmenGeometries {
 public:
  std::shared_ptr<const ScanGeometry> for_scan(const io::CarmenScan& scan) {
    ScanGeometry candidate = io::to_scan_geometry(scan);
    if (!geometry_ || candidate.directions != geometry_->directions ||
        candidate.max_range != geometry_->max_range ||
        !candidate.mount.isApprox(geometry_->mount, 0.0)) {
      geometry_ = std::make_shared<const ScanGeometry>(std::move(candidate));
    }
    return geometry_;
  }

 private:
  std::shared_ptr<const ScanGeometry> geometry_;
};

class CarmenInput : public LogInput {
 public:
  CarmenInput(const std::string& path, HeadingJitter jitter)
      : stream_(path), expected_(count_carmen_scans(path)), jitter_(jitter), random_(jitter.seed) {}

  std::optional<LogEvent> next() override {
    if (pending_.empty()) fill();
    if (pending_.empty()) return std::nullopt;
    LogEvent event = std::move(pending_.front());
    pending_.pop_front();
    return event;
  }
  std::size_t expected_scans() const override { return expected_; }
  std::size_t malformed() const override { return stream_.malformed_lines(); }
  std::vector<std::string> take_problems() override { return stream_.take_new_problems(); }
  double data_seconds() const override { return stamps_.seconds(); }

 private:
  // The three events of one scan: its heading, its odometry position, the scan.
  void fill() {
    std::optional<io::TimedCarmenScan> timed = stream_.next();
    if (!timed) return;
    const io::CarmenScan& carmen = timed->scan;
    const io::CarmenPose2& robot = carmen.robot_pose;
    stamps_.add(carmen.ipc_timestamp);
    LogEvent imu(LogEvent::Kind::Imu);
    imu.imu = {timed->stamp, yaw_rotation(robot.theta + jitter()), Vec3::Zero(), Vec3::Zero()};
    LogEvent odometry(LogEvent::Kind::Odometry);
    odometry.odometry = {timed->stamp, Vec3(robot.x, robot.y, 0.0)};
    LogEvent scan(LogEvent::Kind::Scan);
    scan.scan = io::to_core_scan(carmen, geometries_.for_scan(carmen), timed->index);
    scan.scan.stamp = timed->stamp;
    scan.output_stamp = carmen.ipc_timestamp;
    scan.start_hint = Vec3(robot.x, robot.y, 0.0);
    pending_.push_back(std::move(imu));
    pending_.push_back(std::move(odometry));
    pending_.push_back(std::move(scan));
  }

  double jitter() {
    if (jitter_.amplitude <= 0.0) return 0.0;
    return std::uniform_real_distribution<double>(-jitter_.amplitude, jitter_.amplitude)(random_);
  }

  io::CarmenScanStream stream_;
  std::size_t expected_;
  HeadingJitter jitter_;
  std::mt19937 random_;
  CarmenGeometries geometries_;
  std::deque<LogEvent> pending_;
  StampRange stamps_;
};

// IMU samples up to each scan's stamp come before the scan, as on the vehicle.
class SimulatedInput : public LogInput {
 public:
  explicit SimulatedInput(std::shared_ptr<const SensorLog> log) : log_(std::move(log)) {}

  std::optional<LogEvent> next() override {
    if (scan_ >= log_->scans.size()) return std::nullopt;
    const Scan& scan = log_->scans[scan_];
    if (imu_ < log_->imu.size() && log_->imu[imu_].stamp <= scan.stamp) {
      LogEvent event(LogEvent::Kind::Imu);
      event.imu = log_->imu[imu_++];
      return event;
    }
    LogEvent event(LogEvent::Kind::Scan);
    event.scan = scan;
    event.output_stamp = scan.stamp;
    event.truth = log_->ground_truth[scan_];
    event.start_hint = log_->ground_truth[scan_].position;
    stamps_.add(scan.stamp);
    ++scan_;
    return event;
  }
  std::size_t expected_scans() const override { return log_->scans.size(); }
  double data_seconds() const override { return stamps_.seconds(); }

 private:
  std::shared_ptr<const SensorLog> log_;
  std::size_t scan_ = 0;
  std::size_t imu_ = 0;
  StampRange stamps_;
};

}  // namespace

std::unique_ptr<LogInput> open_carmen_input(const std::string& path, HeadingJitter jitter) {
  return std::make_unique<CarmenInput>(path, jitter);
}

std::unique_ptr<LogInput> open_simulated_input(std::shared_ptr<const SensorLog> log) {
  return std::make_unique<SimulatedInput>(std::move(log));
}

}  // namespace uavslam::cli
