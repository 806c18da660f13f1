#include "sim/Primitives.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace uavslam::sim {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

Ray::Ray(const Vec3& origin_, const Vec3& unit_dir_)
    : origin(origin_), dir(unit_dir_), inv_dir(unit_dir_.cwiseInverse()) {}

double ray_exit_from_box(const Ray& ray, const Box& room) {
  double t_exit = kInf;
  for (int axis = 0; axis < 3; ++axis) {
    if (ray.dir[axis] == 0.0) continue;  // parallel to this pair of faces
    const double face = ray.dir[axis] > 0.0 ? room.max[axis] : room.min[axis];
    t_exit = std::min(t_exit, (face - ray.origin[axis]) * ray.inv_dir[axis]);
  }
  return t_exit;
}

double ray_hit_box(const Ray& ray, const Box& box, double t_max) {
  double t_enter = 0.0;  // starting at 0 makes an origin inside the box a hit at 0
  double t_exit = t_max;
  for (int axis = 0; axis < 3; ++axis) {
    const double o = ray.origin[axis];
    if (ray.dir[axis] == 0.0) {
      // Parallel: an explicit test avoids the 0 * inf = NaN of the branch-free form.
      if (o < box.min[axis] || o > box.max[axis]) return kInf;
      continue;
    }
    double t0 = (box.min[axis] - o) * ray.inv_dir[axis];
    double t1 = (box.max[axis] - o) * ray.inv_dir[axis];
    if (t0 > t1) std::swap(t0, t1);
    t_enter = std::max(t_enter, t0);
    t_exit = std::min(t_exit, t1);
    if (t_enter > t_exit) return kInf;
  }
  return t_enter;
}

double ray_hit_cylinder(const Ray& ray, const Cylinder& cylinder, double t_max) {
  const double ox = ray.origin.x() - cylinder.center.x();
  const double oy = ray.origin.y() - cylinder.center.y();
  const double dx = ray.dir.x();
  const double dy = ray.dir.y();
  const double r2 = cylinder.radius * cylinder.radius;
  const double c = ox * ox + oy * oy - r2;    // > 0: origin outside the circle
  const double half_b = ox * dx + oy * dy;    // >= 0: moving away from the axis
  if (c > 0.0 && half_b >= 0.0) return kInf;  // cheap reject, the common case
  if (cylinder_contains(cylinder, ray.origin)) return 0.0;

  double best = kInf;
  const double a = dx * dx + dy * dy;
  if (c > 0.0 && a > 0.0) {  // side: only reachable from outside the circle
    const double disc = half_b * half_b - a * c;
    if (disc < 0.0) return kInf;  // the line never enters the infinite cylinder
    const double t = (-half_b - std::sqrt(disc)) / a;
    const double z = ray.origin.z() + t * ray.dir.z();
    if (t >= 0.0 && z >= cylinder.z0 && z <= cylinder.z1) best = t;
  }
  if (ray.dir.z() != 0.0) {  // caps
    for (const double cap_z : {cylinder.z0, cylinder.z1}) {
      const double t = (cap_z - ray.origin.z()) * ray.inv_dir.z();
      if (t < 0.0 || t >= best) continue;
      const double px = ox + t * dx;
      const double py = oy + t * dy;
      if (px * px + py * py <= r2) best = t;
    }
  }
  return best <= t_max ? best : kInf;
}

namespace {

// The angle of (x, y) about the arc's centre lies on the arc.
bool on_arc(const ArcWall& arc, double x, double y) {
  const double span = arc.to_deg - arc.from_deg;
  double from_start = std::atan2(y, x) * 180.0 / M_PI - arc.from_deg;
  from_start -= 360.0 * std::floor(from_start / 360.0);
  return from_start <= span;
}

}  // namespace

double ray_hit_arc(const Ray& ray, const ArcWall& arc, double t_max) {
  const double ox = ray.origin.x() - arc.center.x();
  const double oy = ray.origin.y() - arc.center.y();
  const double dx = ray.dir.x(), dy = ray.dir.y();
  const double a = dx * dx + dy * dy;
  if (a == 0.0) return kInf;  // straight up or down: along the wall, never through it
  const double half_b = ox * dx + oy * dy;
  const double c = ox * ox + oy * oy - arc.radius * arc.radius;
  const double disc = half_b * half_b - a * c;
  if (disc < 0.0) return kInf;
  for (const double t : {(-half_b - std::sqrt(disc)) / a, (-half_b + std::sqrt(disc)) / a}) {
    if (t < 0.0 || t > t_max) continue;
    const double z = ray.origin.z() + t * ray.dir.z();
    if (z >= arc.z0 && z <= arc.z1 && on_arc(arc, ox + t * dx, oy + t * dy)) return t;
  }
  return kInf;
}

bool box_contains(const Box& box, const Vec3& p) {
  return (p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all();
}

bool cylinder_contains(const Cylinder& cylinder, const Vec3& p) {
  const Eigen::Vector2d offset = p.head<2>() - cylinder.center;
  return offset.squaredNorm() <= cylinder.radius * cylinder.radius && p.z() >= cylinder.z0 &&
         p.z() <= cylinder.z1;
}

double distance_to_box_surface(const Box& box, const Vec3& p) {
  const Vec3 below = box.min - p;  // > 0 on axes where p is below the box
  const Vec3 above = p - box.max;  // > 0 on axes where p is above the box
  const Vec3 outside = below.cwiseMax(above).cwiseMax(0.0);
  if (outside.squaredNorm() > 0.0) return outside.norm();
  return -below.cwiseMax(above).maxCoeff();  // inside: the nearest face
}

double distance_to_cylinder_surface(const Cylinder& cylinder, const Vec3& p) {
  const double radial = (p.head<2>() - cylinder.center).norm() - cylinder.radius;
  const double vertical = std::max(cylinder.z0 - p.z(), p.z() - cylinder.z1);
  if (radial <= 0.0 && vertical <= 0.0) return std::min(-radial, -vertical);  // inside
  return std::hypot(std::max(radial, 0.0), std::max(vertical, 0.0));
}

double distance_to_arc(const ArcWall& arc, const Vec3& p) {
  const Eigen::Vector2d offset = p.head<2>() - arc.center;
  const double vertical = std::max({arc.z0 - p.z(), p.z() - arc.z1, 0.0});
  if (on_arc(arc, offset.x(), offset.y())) {
    return std::hypot(std::abs(offset.norm() - arc.radius), vertical);
  }
  double nearest = kInf;  // off the arc's span: its nearer end
  for (const double deg : {arc.from_deg, arc.to_deg}) {
    const Eigen::Vector2d end =
        arc.radius * Eigen::Vector2d(std::cos(deg * M_PI / 180.0), std::sin(deg * M_PI / 180.0));
    nearest = std::min(nearest, std::hypot((offset - end).norm(), vertical));
  }
  return nearest;
}

}  // namespace uavslam::sim
