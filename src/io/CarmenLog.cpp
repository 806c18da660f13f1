#include "io/CarmenLog.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>
#include <utility>

#include "io/TextFields.hpp"

namespace uavslam::io {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A line's fields; one malformed field makes the whole message unusable, so a parse failure
// carries the reason out instead of throwing.
class Fields {
 public:
  explicit Fields(std::string_view line) : fields_(split_fields(line)) {}

  std::size_t size() const { return fields_.size(); }
  std::string_view operator[](std::size_t i) const { return fields_[i]; }

  // Parses field i as a finite number; on failure sets error() and returns 0.
  template <typename T>
  T number(std::size_t i, const char* what) {
    T value{};
    if (!parse_number(fields_[i], value)) {
      fail("field " + std::to_string(i + 1) + " (" + what +
           ") is not a finite number: " + quoted(fields_[i]));
      return T{};
    }
    return value;
  }

  // Parses field i as a non-negative beam count.
  std::size_t count(std::size_t i, const char* what) {
    std::size_t value = 0;
    if (!parse_number(fields_[i], value))
      fail(std::string(what) + " is not a count: " + quoted(fields_[i]));
    return value;
  }

  CarmenPose2 pose(std::size_t i, const char* what) {
    return {number<double>(i, what), number<double>(i + 1, what), number<double>(i + 2, what)};
  }

  const std::string& error() const { return error_; }

 private:
  void fail(const std::string& reason) {
    if (error_.empty()) error_ = reason;
  }

  std::vector<std::string_view> fields_;
  std::string error_;
};

// What parsing one line gave: a message, nothing of interest, or the reason it is malformed.
struct LineResult {
  std::optional<CarmenMessage> message;
  std::string problem;
};

LineResult malformed(std::string reason) {
  return {std::nullopt, std::move(reason)};
}

std::string field_count_problem(const char* type, std::size_t expected, std::size_t got) {
  return std::string(type) + ": expected " + std::to_string(expected) + " fields, got " +
         std::to_string(got);
}

std::vector<float> parse_ranges(Fields& f, std::size_t first, std::size_t n) {
  std::vector<float> ranges(n);
  for (std::size_t i = 0; i < n; ++i) ranges[i] = f.number<float>(first + i, "range");
  return ranges;
}

LineResult finish(Fields& f, CarmenMessage message) {
  if (!f.error().empty()) return malformed(f.error());
  return {std::move(message), {}};
}

// FLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp hostname logger_timestamp
LineResult parse_flaser(Fields& f, double max_range) {
  constexpr std::size_t kFixed = 11;
  if (f.size() < 2) return malformed(field_count_problem("FLASER", kFixed, f.size()));
  const std::size_t n = f.count(1, "FLASER beam count");
  if (!f.error().empty()) return malformed(f.error());
  if (n > f.size() || f.size() != n + kFixed) {
    return malformed("FLASER: beam count " + std::to_string(n) + " needs " +
                     std::to_string(n + kFixed) + " fields, got " + std::to_string(f.size()));
  }
  CarmenScan scan;
  scan.message = CarmenScan::Message::flaser;
  scan.start_angle = kFlaserStartAngle;
  scan.angle_increment = flaser_angle_increment(n);
  scan.max_range = max_range;
  scan.ranges = parse_ranges(f, 2, n);
  scan.laser_pose = f.pose(2 + n, "laser pose");
  scan.robot_pose = f.pose(5 + n, "odometry pose");
  scan.ipc_timestamp = f.number<double>(8 + n, "ipc_timestamp");
  f.number<double>(10 + n, "logger_timestamp");
  return finish(f, std::move(scan));
}

// ROBOTLASER1 type start_angle fov resolution max_range accuracy remission_mode n r1..rn
//   m rem1..remm laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv forward_safety
//   side_safety turn_axis ipc_timestamp hostname logger_timestamp
LineResult parse_robotlaser1(Fields& f) {
  constexpr std::size_t kBeforeRanges = 9;
  constexpr std::size_t kAfterRemissions = 14;
  if (f.size() < kBeforeRanges + 1 + kAfterRemissions) {
    return malformed(
        field_count_problem("ROBOTLASER1", kBeforeRanges + 1 + kAfterRemissions, f.size()));
  }
  const std::size_t n = f.count(8, "ROBOTLASER1 beam count");
  if (!f.error().empty()) return malformed(f.error());
  if (n > f.size() || f.size() < kBeforeRanges + n + 1 + kAfterRemissions) {
    return malformed("ROBOTLASER1: beam count " + std::to_string(n) + " needs at least " +
                     std::to_string(kBeforeRanges + n + 1 + kAfterRemissions) + " fields, got " +
                     std::to_string(f.size()));
  }
  const std::size_t m = f.count(kBeforeRanges + n, "ROBOTLASER1 remission count");
  if (!f.error().empty()) return malformed(f.error());
  const std::size_t expected = kBeforeRanges + n + 1 + m + kAfterRemissions;
  if (m > f.size() || f.size() != expected) {
    return malformed("ROBOTLASER1: beam count " + std::to_string(n) + " and remission count " +
                     std::to_string(m) + " need " + std::to_string(expected) + " fields, got " +
                     std::to_string(f.size()));
  }
  CarmenScan scan;
  scan.message = CarmenScan::Message::robotlaser1;
  scan.start_angle = f.number<double>(2, "start_angle");
  f.number<double>(3, "fov");
  scan.angle_increment = f.number<double>(4, "resolution");
  scan.max_range = f.number<double>(5, "max_range");
  scan.ranges = parse_ranges(f, kBeforeRanges, n);
  const std::size_t tail = kBeforeRanges + n + 1 + m;
  for (std::size_t i = kBeforeRanges + n + 1; i < tail; ++i) f.number<double>(i, "remission");
  scan.laser_pose = f.pose(tail, "laser pose");
  scan.robot_pose = f.pose(tail + 3, "robot pose");
  scan.ipc_timestamp = f.number<double>(tail + 11, "ipc_timestamp");
  f.number<double>(tail + 13, "logger_timestamp");
  return finish(f, std::move(scan));
}

// ODOM x y theta tv rv accel ipc_timestamp hostname logger_timestamp
LineResult parse_odom(Fields& f) {
  constexpr std::size_t kFields = 10;
  if (f.size() != kFields) return malformed(field_count_problem("ODOM", kFields, f.size()));
  CarmenOdometry odom;
  odom.pose = f.pose(1, "pose");
  odom.tv = f.number<double>(4, "tv");
  odom.rv = f.number<double>(5, "rv");
  f.number<double>(6, "accel");
  odom.ipc_timestamp = f.number<double>(7, "ipc_timestamp");
  f.number<double>(9, "logger_timestamp");
  return finish(f, std::move(odom));
}

LineResult parse_line(std::string_view line, double flaser_max_range) {
  Fields f(line);
  if (f.size() == 0 || f[0].front() == '#') return {};
  if (f[0] == "FLASER") return parse_flaser(f, flaser_max_range);
  if (f[0] == "ROBOTLASER1") return parse_robotlaser1(f);
  if (f[0] == "ODOM") return parse_odom(f);
  return {};
}

}  // namespace

bool CarmenScan::is_return(std::size_t i) const {
  // Compared in float, the precision the ranges were read with, so that a range written as the
  // max_range value itself (e.g. 81.83) counts as no return.
  const float r = ranges[i];
  return std::isfinite(r) && r < static_cast<float>(max_range);
}

double flaser_angle_increment(std::size_t beams) {
  if (beams == 180) return kPi / 180.0;
  if (beams == 360) return kPi / 360.0;
  if (beams < 2) return 0.0;
  return kPi / static_cast<double>(beams - 1);
}

CarmenLogReader::CarmenLogReader(const std::string& path) : path_(path), in_(path) {
  if (!in_) throw file_error(path, std::string("cannot open: ") + std::strerror(errno));
  flaser_no_return_ = learn_flaser_no_return_code(path);
}

double CarmenLogReader::flaser_max_range() const {
  return flaser_no_return_ ? static_cast<double>(flaser_no_return_->range) : kFlaserMaxRange;
}

std::optional<CarmenMessage> CarmenLogReader::next() {
  while (std::getline(in_, text_)) {
    ++line_;
    LineResult result = parse_line(text_, flaser_max_range());
    if (!result.problem.empty()) {
      report(result.problem);
      continue;
    }
    if (result.message) {
      std::visit([this](auto& m) { m.line = line_; }, *result.message);
      return std::move(result.message);
    }
  }
  if (in_.bad()) throw line_error(path_, line_ + 1, "read error");
  return std::nullopt;
}

void CarmenLogReader::report(const std::string& reason) {
  ++malformed_lines_;
  if (problems_.size() < kMaxReportedProblems) {
    problems_.push_back(path_ + ":" + std::to_string(line_) + ": " + reason);
  }
}

CarmenLog read_carmen_log(const std::string& path) {
  CarmenLogReader reader(path);
  CarmenLog log;
  while (std::optional<CarmenMessage> message = reader.next()) {
    log.messages.push_back(std::move(*message));
  }
  log.malformed_lines = reader.malformed_lines();
  log.problems = reader.problems();
  log.flaser_no_return = reader.flaser_no_return();
  return log;
}

Eigen::Isometry3d laser_mount(const CarmenScan& scan) {
  const CarmenPose2& robot = scan.robot_pose;
  const CarmenPose2& laser = scan.laser_pose;
  const double c = std::cos(robot.theta);
  const double s = std::sin(robot.theta);
  const double dx = laser.x - robot.x;
  const double dy = laser.y - robot.y;
  // The logs print 6 decimals: rounded, every scan of a log gets the same mount.
  const auto round = [](double v) { return std::round(v * 1e3) / 1e3; };
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.translation() = Vec3(round(c * dx + s * dy), round(-s * dx + c * dy), 0.0);
  mount.linear() =
      Eigen::AngleAxisd(round(std::remainder(laser.theta - robot.theta, 2.0 * M_PI)), Vec3::UnitZ())
          .toRotationMatrix();
  return mount;
}

ScanGeometry to_scan_geometry(const CarmenScan& scan) {
  ScanGeometry geometry = ScanGeometry::planar(scan.start_angle, scan.angle_increment,
                                               static_cast<int>(scan.ranges.size()));
  geometry.mount = laser_mount(scan);
  // The core keeps ranges <= max_range; the largest float below max_range keeps exactly the
  // ranges that is_return() accepts.
  geometry.max_range = std::nextafter(static_cast<float>(scan.max_range), 0.0f);
  return geometry;
}

Scan to_core_scan(const CarmenScan& scan, std::shared_ptr<const ScanGeometry> geometry,
                  std::uint64_t sequence) {
  Scan core;
  core.stamp = scan.ipc_timestamp;
  core.sequence = sequence;
  core.geometry = std::move(geometry);
  core.ranges = scan.ranges;
  return core;
}

}  // namespace uavslam::io
