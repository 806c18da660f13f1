// Ray and distance queries on the world's primitive shapes, kept free of any world bookkeeping so
// the ray-caster's inner loop stays small.
#pragma once

#include "core/Types.hpp"
#include "sim/Scenario.hpp"

namespace uavslam::sim {

// A ray with its per-axis reciprocal direction precomputed (used by every slab test).
struct Ray {
  Ray(const Vec3& origin_, const Vec3& unit_dir_);
  Vec3 origin;
  Vec3 dir;
  Vec3 inv_dir;  // 1/dir; +-infinity on axes the ray is parallel to
};

// Distance at which a ray starting inside `room` leaves it through one of its faces.
double ray_exit_from_box(const Ray& ray, const Box& room);

// Distance to the first hit on a solid box, or +infinity if none before `t_max`
// (0 when the origin is inside the box).
double ray_hit_box(const Ray& ray, const Box& box, double t_max);

// Distance to the first hit on a solid vertical cylinder (side or caps), or +infinity if none
// before `t_max` (0 when the origin is inside the cylinder).
double ray_hit_cylinder(const Ray& ray, const Cylinder& cylinder, double t_max);

// Distance to the first hit on an arc wall (from either side), or +infinity if none before t_max.
double ray_hit_arc(const Ray& ray, const ArcWall& arc, double t_max);

bool box_contains(const Box& box, const Vec3& p);
bool cylinder_contains(const Cylinder& cylinder, const Vec3& p);

// Euclidean distance from p to the surface of a box / cylinder, whether p is inside or outside.
double distance_to_box_surface(const Box& box, const Vec3& p);
double distance_to_cylinder_surface(const Cylinder& cylinder, const Vec3& p);
double distance_to_arc(const ArcWall& arc, const Vec3& p);

}  // namespace uavslam::sim
