// An 8-bit RGB raster, row-major from the top-left pixel, as image files store it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace uavslam::io {

using Rgb = std::array<std::uint8_t, 3>;

class RgbImage {
 public:
  // Throws std::invalid_argument for a non-positive size.
  RgbImage(int width, int height, Rgb fill = {255, 255, 255}) : width_(width), height_(height) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("RgbImage: size must be positive");
    pixels_.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
    for (std::size_t i = 0; i < pixels_.size(); i += 3) {
      pixels_[i] = fill[0];
      pixels_[i + 1] = fill[1];
      pixels_[i + 2] = fill[2];
    }
  }

  int width() const { return width_; }
  int height() const { return height_; }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }

  // Throws std::out_of_range outside the image.
  Rgb at(int x, int y) const {
    if (!contains(x, y)) throw std::out_of_range("RgbImage::at: pixel outside the image");
    const std::size_t i = index(x, y);
    return {pixels_[i], pixels_[i + 1], pixels_[i + 2]};
  }
  // Pixels outside the image are ignored, so shapes may be drawn partly off the edge.
  void set(int x, int y, Rgb colour) {
    if (!contains(x, y)) return;
    const std::size_t i = index(x, y);
    pixels_[i] = colour[0];
    pixels_[i + 1] = colour[1];
    pixels_[i + 2] = colour[2];
  }

  // width * height * 3 bytes, R G B per pixel.
  const std::vector<std::uint8_t>& bytes() const { return pixels_; }

 private:
  std::size_t index(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
            static_cast<std::size_t>(x)) *
           3;
  }

  int width_;
  int height_;
  std::vector<std::uint8_t> pixels_;
};

}  // namespace uavslam::io
