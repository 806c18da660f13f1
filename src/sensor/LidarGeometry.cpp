#include "sensor/LidarGeometry.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/Angles.hpp"

namespace uavslam {

namespace {

double even_step(double span, int count) {
  return count > 1 ? span / (count - 1) : 0.0;
}

double first_beam_azimuth(const LidarSpec& spec) {
  return -deg_to_rad(spec.fov_deg) / 2.0;
}

double beam_increment(const LidarSpec& spec) {
  return even_step(deg_to_rad(spec.fov_deg), spec.beams);
}

// A fan pointing to -z, spread across the vertical plane that holds the first beam (at `azimuth`).
void deflect_into_floor_mirror(const LidarSpec& spec, double azimuth,
                               std::vector<Vec3>& directions) {
  const int mirrored = std::min(spec.floor_mirror.beams, static_cast<int>(directions.size()));
  const double spread = deg_to_rad(spec.floor_mirror.spread_deg);
  const double step = even_step(spread, mirrored);
  const double first = mirrored > 1 ? -spread / 2.0 : 0.0;
  for (int i = 0; i < mirrored; ++i) {
    const double s = first + i * step;
    directions[static_cast<std::size_t>(i)] =
        Vec3(std::sin(s) * std::cos(azimuth), std::sin(s) * std::sin(azimuth), -std::cos(s));
  }
}

std::vector<Vec3> multi_ring_directions(const LidarSpec& spec) {
  const double vertical_fov = deg_to_rad(spec.vertical_fov_deg);
  const double ring_step = even_step(vertical_fov, spec.rings);
  std::vector<Vec3> directions;
  directions.reserve(static_cast<std::size_t>(spec.beams) * static_cast<std::size_t>(spec.rings));
  for (int ring = 0; ring < spec.rings; ++ring) {
    const double elevation = -vertical_fov / 2.0 + ring * ring_step;
    for (int beam = 0; beam < spec.beams; ++beam) {
      const double azimuth = first_beam_azimuth(spec) + beam * beam_increment(spec);
      directions.emplace_back(std::cos(elevation) * std::cos(azimuth),
                              std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
    }
  }
  return directions;
}

// The rings fire together at each azimuth, the azimuths in turn (a spinning multi-ring scanner).
std::vector<double> multi_ring_fire_times(const LidarSpec& spec) {
  const double step = even_step(spec.sweep_seconds, spec.beams);
  std::vector<double> times;
  if (spec.sweep_seconds <= 0.0) return times;
  times.reserve(static_cast<std::size_t>(spec.beams) * static_cast<std::size_t>(spec.rings));
  for (int ring = 0; ring < spec.rings; ++ring) {
    for (int beam = 0; beam < spec.beams; ++beam) times.push_back(beam * step);
  }
  return times;
}

}  // namespace

Eigen::Isometry3d lidar_mount(const LidarSpec& spec) {
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.linear() = rotation_from_rpy_deg(spec.mount_rpy_deg).toRotationMatrix();
  mount.translation() = spec.mount_position;
  return mount;
}

ScanGeometry planar_scan_geometry(const LidarSpec& spec, double angle_min, double angle_increment,
                                  int beams) {
  ScanGeometry geometry = ScanGeometry::planar(angle_min, angle_increment, beams);
  if (spec.floor_mirror.beams > 0) deflect_into_floor_mirror(spec, angle_min, geometry.directions);
  geometry.min_range = spec.min_range;
  geometry.max_range = spec.max_range;
  geometry.mount = lidar_mount(spec);
  // The mirror turns at one rate: a layout's beams sweep as many seconds per radian as the spec's.
  const double fov = deg_to_rad(spec.fov_deg);
  if (spec.sweep_seconds > 0.0 && fov > 0.0) {
    geometry.sweep_beams_in_order(spec.sweep_seconds * std::abs(angle_increment) / fov);
  }
  return geometry;
}

std::shared_ptr<const ScanGeometry> make_scan_geometry(const LidarSpec& spec) {
  ScanGeometry geometry =
      planar_scan_geometry(spec, first_beam_azimuth(spec), beam_increment(spec), spec.beams);
  if (spec.rings > 1) {  // and no mirror
    geometry.directions = multi_ring_directions(spec);
    geometry.fire_times = multi_ring_fire_times(spec);
  }
  return std::make_shared<const ScanGeometry>(std::move(geometry));
}

}  // namespace uavslam
