// The simulated environment: a room with solid boxes, vertical cylinders and round walls (arcs,
// of no thickness) in it, and people walking through it.
// Answers the two questions the simulator and the map grader ask: where does a ray hit, and how
// far is a point from the nearest surface.
#pragma once

#include <vector>

#include "core/Types.hpp"
#include "sim/Scenario.hpp"

namespace uavslam::sim {

class World {
 public:
  explicit World(const WorldSpec& spec);

  // Distance along unit_dir from origin (inside the room) to the first surface, the people where
  // they are `time` s into the flight, or +infinity when nothing is hit within max_range.
  double cast_ray(const Vec3& origin, const Vec3& unit_dir, double max_range, double time) const;

  // Inside the room and outside every obstacle (the fixed world's: the people are not asked).
  bool is_free(const Vec3& p) const;

  // Exact Euclidean distance to the nearest surface: room faces, box and cylinder surfaces (the
  // fixed world, what a map should hold).
  double distance_to_nearest_surface(const Vec3& p) const;

  // As above but over the obstacles only (boxes, cylinders, arcs), ignoring the room's faces;
  // +infinity when there are none.
  double distance_to_nearest_obstacle(const Vec3& p) const;

  const WorldSpec& spec() const { return spec_; }

 private:
  WorldSpec spec_;
};

}  // namespace uavslam::sim
