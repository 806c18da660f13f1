// RGB images as PNG files (libpng), for the ground station's map picture.
#pragma once

#include <string>

#include "io/FileError.hpp"
#include "io/RgbImage.hpp"

namespace uavslam::io {

// Writes 8-bit RGB PNG. Throws FileError "<path>: cannot open for writing: <reason>" when the file
// cannot be created, and "<path>: <libpng's message>" when encoding or writing fails.
void write_png(const std::string& path, const RgbImage& image);

// Reads any PNG libpng understands, converted to 8-bit RGB (alpha dropped onto white). Throws
// FileError "<path>: <reason>" for a missing or undecodable file.
RgbImage read_png(const std::string& path);

}  // namespace uavslam::io
