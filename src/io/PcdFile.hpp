// Point clouds in PCL's PCD format, version 0.7 (pointclouds.org/documentation/tutorials/
// pcd_file_format.html), the format PCL, Open3D and CloudCompare read natively.
#pragma once

#include <string>
#include <vector>

#include "io/FileError.hpp"
#include "maps/DenseCloud.hpp"

namespace uavslam::io {

// Binary PCD with the fields x y z intensity (float32) and time (float64, seconds), one point per
// DensePoint, as an unorganised cloud (HEIGHT 1). Throws FileError naming the path and the
// system's reason when it cannot be written.
void write_pcd(const std::string& path, const std::vector<DensePoint>& points);

// Reads the points of an ascii or binary PCD file: x y z (float32 or float64) and, when present,
// intensity and time; missing fields read as 0. Throws FileError "<path>: <problem>" on a bad
// header (missing field, sizes that disagree, binary_compressed) or data shorter than it says.
std::vector<DensePoint> read_pcd(const std::string& path);

}  // namespace uavslam::io
