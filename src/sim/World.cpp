#include "sim/World.hpp"

#include <algorithm>
#include <limits>

#include "sim/Primitives.hpp"
#include "sim/Walker.hpp"

namespace uavslam::sim {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

World::World(const WorldSpec& spec) : spec_(spec) {}

double World::cast_ray(const Vec3& origin, const Vec3& unit_dir, double max_range,
                       double time) const {
  const Ray ray(origin, unit_dir);
  const double room_exit = ray_exit_from_box(ray, spec_.room);
  double hit = room_exit <= max_range ? room_exit : kInf;
  // Each obstacle only needs to beat the nearest hit so far, which lets slab tests exit early.
  double limit = std::min(room_exit, max_range);
  for (const Box& box : spec_.boxes) {
    const double t = ray_hit_box(ray, box, limit);
    if (t < hit) hit = limit = t;
  }
  for (const Cylinder& cylinder : spec_.cylinders) {
    const double t = ray_hit_cylinder(ray, cylinder, limit);
    if (t < hit) hit = limit = t;
  }
  for (const ArcWall& arc : spec_.arcs) {
    const double t = ray_hit_arc(ray, arc, limit);
    if (t < hit) hit = limit = t;
  }
  for (const Walker& walker : spec_.people) {
    const Cylinder body = walker_at(walker, time);
    // A person walking through the scanner hides nothing from it (the scan's origin inside).
    if (cylinder_contains(body, origin)) continue;
    const double t = ray_hit_cylinder(ray, body, limit);
    if (t < hit) hit = limit = t;
  }
  return hit;
}

bool World::is_free(const Vec3& p) const {
  if (!box_contains(spec_.room, p)) return false;
  for (const Box& box : spec_.boxes) {
    if (box_contains(box, p)) return false;
  }
  for (const Cylinder& cylinder : spec_.cylinders) {
    if (cylinder_contains(cylinder, p)) return false;
  }
  return true;
}

double World::distance_to_nearest_surface(const Vec3& p) const {
  return std::min(distance_to_box_surface(spec_.room, p), distance_to_nearest_obstacle(p));
}

double World::distance_to_nearest_obstacle(const Vec3& p) const {
  double nearest = kInf;
  for (const Box& box : spec_.boxes) {
    nearest = std::min(nearest, distance_to_box_surface(box, p));
  }
  for (const Cylinder& cylinder : spec_.cylinders) {
    nearest = std::min(nearest, distance_to_cylinder_surface(cylinder, p));
  }
  for (const ArcWall& arc : spec_.arcs) nearest = std::min(nearest, distance_to_arc(arc, p));
  return nearest;
}

}  // namespace uavslam::sim
