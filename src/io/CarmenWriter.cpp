#include "io/CarmenWriter.hpp"

#include <cmath>
#include <cstdio>

#include "io/OutputFile.hpp"

namespace uavslam::io {
namespace {

constexpr const char* kHost = "uavslam-sim";

void write_pose(std::FILE* out, const CarmenPose2& pose) {
  std::fprintf(out, " %.6f %.6f %.6f", pose.x, pose.y, pose.theta);
}

void write_stamps(std::FILE* out, double ipc_timestamp) {
  std::fprintf(out, " %.6f %s %.6f\n", ipc_timestamp, kHost, ipc_timestamp);
}

// ROBOTLASER1 type start_angle fov resolution max_range accuracy remission_mode n r1..rn m
//   laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv forward_safety side_safety
//   turn_axis ipc_timestamp hostname logger_timestamp
void write_scan(std::FILE* out, const CarmenScan& scan) {
  const std::size_t n = scan.ranges.size();
  const double fov = n > 1 ? static_cast<double>(n - 1) * scan.angle_increment : 0.0;
  std::fprintf(out, "ROBOTLASER1 0 %.6f %.6f %.6f %.3f 0.01 0 %zu", scan.start_angle, fov,
               scan.angle_increment, scan.max_range, n);
  for (const float r : scan.ranges) {
    std::fprintf(out, " %.3f", std::isfinite(r) && r < scan.max_range ? r : scan.max_range);
  }
  std::fprintf(out, " 0");
  write_pose(out, scan.laser_pose);
  write_pose(out, scan.robot_pose);
  std::fprintf(out, " 0 0 0 0 0");
  write_stamps(out, scan.ipc_timestamp);
}

// ODOM x y theta tv rv accel ipc_timestamp hostname logger_timestamp
void write_odometry(std::FILE* out, const CarmenOdometry& odometry) {
  std::fprintf(out, "ODOM");
  write_pose(out, odometry.pose);
  std::fprintf(out, " %.6f %.6f 0", odometry.tv, odometry.rv);
  write_stamps(out, odometry.ipc_timestamp);
}

}  // namespace

void write_carmen_log(const std::string& path, const std::vector<std::string>& comments,
                      const std::vector<CarmenMessage>& messages) {
  OutputFile file(path, "w");
  for (const std::string& comment : comments)
    std::fprintf(file.stream(), "# %s\n", comment.c_str());
  for (const CarmenMessage& message : messages) {
    if (const auto* scan = std::get_if<CarmenScan>(&message)) {
      write_scan(file.stream(), *scan);
    } else {
      write_odometry(file.stream(), std::get<CarmenOdometry>(message));
    }
  }
  file.close();
}

}  // namespace uavslam::io
