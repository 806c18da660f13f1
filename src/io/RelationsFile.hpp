// The files of the Freiburg SLAM benchmark (Kümmerle et al. 2009): relations "t1 t2 x y z roll
// pitch yaw" (the true motion from scan t1 to scan t2 in the frame of the pose at t1) and planar
// estimates "timestamp x y theta" to score against them; '#' starts a comment.
#pragma once

#include <string>
#include <vector>

#include "eval/Relation.hpp"
#include "io/FileError.hpp"

namespace uavslam::io {

// Reads every relation in file order; z, roll and pitch are read and dropped (0 in 2D).
// Throws FileError "<path>:<line>: <problem>" on a line that is not 8 finite numbers and
// "<path>: cannot open: <reason>" on an unreadable file.
std::vector<eval::Relation> read_relations(const std::string& path);

// Writes "t1 t2 x y z roll pitch yaw" per relation (z, roll and pitch 0), 6 decimals, in the given
// order. Throws FileError naming the path and the system's reason when it cannot be written.
void write_relations(const std::string& path, const std::vector<eval::Relation>& relations);

// Reads every pose "timestamp x y theta" in file order (stamps need not be monotonic).
// Throws FileError "<path>:<line>: <problem>" on a line that is not 4 finite numbers and
// "<path>: cannot open: <reason>" on an unreadable file.
std::vector<eval::PlanarStamped> read_planar_estimate(const std::string& path);

// Writes "timestamp x y theta" per pose, 6 decimals (micrometres, microradians), in the given
// order. Throws FileError naming the path and the system's reason when it cannot be written.
void write_planar_estimate(const std::string& path, const std::vector<eval::PlanarStamped>& poses);

}  // namespace uavslam::io
