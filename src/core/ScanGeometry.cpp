#include <algorithm>
#include <cmath>

#include "core/Types.hpp"

namespace uavslam {

ScanGeometry ScanGeometry::planar(double angle_min, double angle_increment, int beams) {
  ScanGeometry g;
  g.directions.reserve(static_cast<std::size_t>(beams));
  for (int i = 0; i < beams; ++i) {
    const double a = angle_min + i * angle_increment;
    g.directions.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  return g;
}

void ScanGeometry::sweep_beams_in_order(double time_increment) {
  fire_times.clear();
  if (time_increment <= 0.0) return;
  fire_times.reserve(directions.size());
  for (std::size_t i = 0; i < directions.size(); ++i)
    fire_times.push_back(time_increment * double(i));
}

double ScanGeometry::sweep_seconds() const {
  if (fire_times.empty()) return 0.0;
  const auto [first, last] = std::minmax_element(fire_times.begin(), fire_times.end());
  return *last - *first;
}

bool ScanGeometry::has_vertical_beams() const {
  return std::any_of(directions.begin(), directions.end(),
                     [&](const Vec3& d) { return is_vertical(mount.linear() * d); });
}

}  // namespace uavslam
