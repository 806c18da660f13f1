// The beam layout of a LiDAR described by a LidarSpec (real or simulated): a planar scanner,
// optionally with a floor mirror, or a multi-ring scanner, mounted on the body.
#pragma once

#include <memory>

#include "core/Types.hpp"
#include "sensor/LidarSpec.hpp"

namespace uavslam {

// Planar: beams over fov_deg centred on the sensor x axis. With floor_mirror.beams > 0 the first
// beams fan downwards in the vertical plane of the first beam's azimuth. With rings > 1:
// beams x rings directions, ring-major, elevations evenly over +-vertical_fov/2 (no mirror).
std::shared_ptr<const ScanGeometry> make_scan_geometry(const LidarSpec& spec);

// A planar scanner with the beam layout its scans report (beam i at angle_min + i *
// angle_increment), mounted, mirrored and range-limited as `spec` says: a real sensor's layout can
// differ from the configured one (a UTM-30LX sends 1081 steps of 0.25 deg; the simulated one has
// 1080 over the same 270 deg) while its place on the vehicle does not.
ScanGeometry planar_scan_geometry(const LidarSpec& spec, double angle_min, double angle_increment,
                                  int beams);

// Sensor frame -> body frame from mount_position and mount_rpy_deg (R = Rz * Ry * Rx).
Eigen::Isometry3d lidar_mount(const LidarSpec& spec);

}  // namespace uavslam
