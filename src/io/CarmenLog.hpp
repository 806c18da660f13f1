// CARMEN log files (.clf), the text format of the Freiburg/Intel 2D laser SLAM benchmark logs.
// One message per line, fields separated by white space, `#` starts a comment line:
//
//   FLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp hostname logger_timestamp
//   ROBOTLASER1 type start_angle fov resolution max_range accuracy remission_mode
//               n r1..rn m rem1..remm laser_x laser_y laser_theta robot_x robot_y robot_theta
//               tv rv forward_safety side_safety turn_axis ipc_timestamp hostname logger_timestamp
//   ODOM x y theta tv rv accel ipc_timestamp hostname logger_timestamp
//
// Only these three are read; every other message (PARAM, SYNC, TRUEPOS, ...) is skipped.
// Messages are kept in FILE ORDER, never sorted: the file order is the capture order, while the
// ipc_timestamps may run backwards (intel.clf: 631 times). Each message keeps its own timestamp.
//
// A malformed line (too few or too many fields, a non-number, a beam count that does not match
// the fields) is skipped, counted and described as "path:line: reason"; it never throws.
// Only a file that cannot be opened or read throws io::FileError.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/Types.hpp"
#include "io/FileError.hpp"
#include "io/NoReturnCode.hpp"

namespace uavslam::io {

// FLASER carries no maximum range: the reader learns the log's no-return code from its ranges
// (NoReturnCode.hpp). Without one (every beam returned), the default is the SICK LMS 2xx's: it
// reports a missing return as a reserved code at the top of its 13-bit centimetre range
// (8183..8191 cm; intel.clf writes 81.83, fr079.clf 81.91).
inline constexpr double kFlaserMaxRange = 81.83;  // m

// The number of problem descriptions kept; malformed_lines counts them all.
inline constexpr std::size_t kMaxReportedProblems = 20;

struct CarmenPose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;  // rad
};

// One laser scan (FLASER or ROBOTLASER1). Beam i points at start_angle + i * angle_increment in
// the laser frame (x forward, y left).
struct CarmenScan {
  enum class Message { flaser, robotlaser1 };
  Message message = Message::flaser;
  double ipc_timestamp = 0.0;  // s
  double start_angle = 0.0;    // rad
  double angle_increment = 0.0;
  double max_range = kFlaserMaxRange;  // m; ranges >= max_range are "no return"
  std::vector<float> ranges;           // m
  CarmenPose2 laser_pose;              // the laser in the odometry frame
  CarmenPose2 robot_pose;              // the robot (odometry) pose given in the same message
  std::size_t line = 0;                // 1-based line in the file

  double beam_angle(std::size_t i) const {
    return start_angle + static_cast<double>(i) * angle_increment;
  }
  bool is_return(std::size_t i) const;
};

struct CarmenOdometry {
  CarmenPose2 pose;
  double tv = 0.0;             // m/s
  double rv = 0.0;             // rad/s
  double ipc_timestamp = 0.0;  // s
  std::size_t line = 0;
};

using CarmenMessage = std::variant<CarmenScan, CarmenOdometry>;

// The FLASER beam angles, CARMEN's rule (its laser interface library:
// carmen_laser_get_angle_increment / carmen_laser_get_fov, with start_angle = -90 deg):
// 180 beams step 1 deg and 360 beams step 0.5 deg, both over [-90 deg, +90 deg) (CARMEN: "last
// beam ignored"); any other count n spans 180 deg inclusively, step 180 deg / (n - 1), so 181
// beams step 1 deg and 361 beams 0.5 deg over [-90 deg, +90 deg]. (CARMEN's 100 deg special
// case for 400/401 beams belongs to other scanners and is not applied to FLASER here.)
double flaser_angle_increment(std::size_t beams);
inline constexpr double kFlaserStartAngle = -1.5707963267948966;  // -90 deg

// Reads a log message by message, for logs too large to hold. Lines that are not messages of
// interest are passed over; malformed ones are counted and described.
class CarmenLogReader {
 public:
  // Throws FileError naming the path when it cannot be opened. Reads the file once first, to
  // learn its FLASER no-return code.
  explicit CarmenLogReader(const std::string& path);

  // The next FLASER/ROBOTLASER1/ODOM message in file order; nullopt at the end of the file.
  std::optional<CarmenMessage> next();

  std::size_t malformed_lines() const { return malformed_lines_; }
  const std::vector<std::string>& problems() const { return problems_; }
  // The FLASER no-return code learned from the log; none if every beam returned.
  const std::optional<NoReturnCode>& flaser_no_return() const { return flaser_no_return_; }
  // FLASER ranges at or above this are no return: the learned code, or kFlaserMaxRange.
  double flaser_max_range() const;

 private:
  void report(const std::string& reason);

  std::string path_;
  std::ifstream in_;
  std::string text_;
  std::size_t line_ = 0;
  std::size_t malformed_lines_ = 0;
  std::vector<std::string> problems_;
  std::optional<NoReturnCode> flaser_no_return_;
};

struct CarmenLog {
  std::vector<CarmenMessage> messages;  // file order
  std::size_t malformed_lines = 0;
  std::vector<std::string> problems;  // the first kMaxReportedProblems, "path:line: reason"
  std::optional<NoReturnCode> flaser_no_return;
};

CarmenLog read_carmen_log(const std::string& path);

// Where the laser sits on the robot, from the two poses the message gives (laser and robot in the
// odometry frame), rounded to 1 mm and 1 mrad: FR079's laser is 0.04 m behind the odometry
// centre (its PARAM robot_frontlaser_offset), Intel's at the centre.
Eigen::Isometry3d laser_mount(const CarmenScan& scan);

// The core's view of a CARMEN scan: a planar scanner with the scan's beam angles, mounted on the
// robot (the body) at laser_mount; valid ranges are those below the scan's max_range.
ScanGeometry to_scan_geometry(const CarmenScan& scan);
// The scan on a geometry made by to_scan_geometry (shared by the scans of one log).
Scan to_core_scan(const CarmenScan& scan, std::shared_ptr<const ScanGeometry> geometry,
                  std::uint64_t sequence);

}  // namespace uavslam::io
