// Point clouds in the PLY format (Turk 1994, paulbourke.net/dataformats/ply) as CloudCompare,
// MeshLab and Open3D read them: one "vertex" element with float properties x y z.
#pragma once

#include <string>
#include <vector>

#include "core/Types.hpp"
#include "io/FileError.hpp"
#include "maps/DenseCloud.hpp"

namespace uavslam::io {

// Writes binary_little_endian PLY with float x y z per point (metres, narrowed to float).
// Throws FileError naming the path and the system's reason when the file cannot be written.
void write_ply(const std::string& path, const Points& points);

// The same with an extra float "intensity" property per point; throws std::invalid_argument
// unless there is exactly one intensity per point.
void write_ply(const std::string& path, const Points& points,
               const std::vector<float>& intensities);

// A dense cloud (the offline mapper's): float x y z intensity and double time (seconds) per
// point, binary_little_endian.
void write_ply(const std::string& path, const std::vector<DensePoint>& points);

// Reads the x y z of every vertex of an ascii or binary_little_endian PLY file. x, y and z must be
// float or double properties; other vertex properties and other elements are skipped. Throws
// FileError "<path>:<line>: <problem>" on a bad header or data that does not match it.
Points read_ply(const std::string& path);

}  // namespace uavslam::io
