#include "io/PngFile.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

namespace uavslam::io {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

// libpng's simplified API (1.6) reports errors through png_image::message instead of longjmp,
// which would skip C++ destructors.
struct PngImage {
  png_image image{};
  PngImage() { image.version = PNG_IMAGE_VERSION; }
  ~PngImage() { png_image_free(&image); }
  PngImage(const PngImage&) = delete;
  PngImage& operator=(const PngImage&) = delete;
};

}  // namespace

void write_png(const std::string& path, const RgbImage& image) {
  // Opened here rather than by libpng so the message carries the system's reason.
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (!file)
    throw file_error(path, std::string("cannot open for writing: ") + std::strerror(errno));
  PngImage png;
  png.image.width = static_cast<png_uint_32>(image.width());
  png.image.height = static_cast<png_uint_32>(image.height());
  png.image.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_stdio(&png.image, file.get(), 0, image.bytes().data(), 0, nullptr)) {
    throw file_error(path, std::string("cannot write PNG: ") + png.image.message);
  }
  if (std::fflush(file.get()) != 0 || std::ferror(file.get())) {
    throw file_error(path, std::string("cannot write: ") + std::strerror(errno));
  }
}

RgbImage read_png(const std::string& path) {
  PngImage png;
  if (!png_image_begin_read_from_file(&png.image, path.c_str())) {
    throw file_error(path, std::string("cannot read PNG: ") + png.image.message);
  }
  png.image.format = PNG_FORMAT_RGB;
  const int width = static_cast<int>(png.image.width);
  const int height = static_cast<int>(png.image.height);
  std::vector<png_byte> bytes(PNG_IMAGE_SIZE(png.image));
  const png_color white{255, 255, 255};
  if (!png_image_finish_read(&png.image, &white, bytes.data(), 0, nullptr)) {
    throw file_error(path, std::string("cannot decode PNG: ") + png.image.message);
  }
  RgbImage result(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                             static_cast<std::size_t>(x)) *
                            3;
      result.set(x, y, {bytes[i], bytes[i + 1], bytes[i + 2]});
    }
  }
  return result;
}

}  // namespace uavslam::io
