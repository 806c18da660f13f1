#include "io/TopDownMapImage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace uavslam::io {
namespace {

constexpr Rgb kFree{225, 225, 225};
constexpr Rgb kPath{20, 90, 230};
constexpr Rgb kStart{30, 170, 60};
constexpr Rgb kEnd{220, 30, 30};
constexpr Rgb kBlack{0, 0, 0};
constexpr int kLightestOccupied = 160;  // grey of a column with a single occupied cell
constexpr int kMarkerRadiusPx = 6;
constexpr int kPathHalfWidthPx = 1;
// Beyond this many columns the map is summarised on a coarser grid (2, 4, ... cells across), so
// a very large map costs bounded memory; the drawing is then coarser than the map, not wrong.
constexpr std::size_t kMaxColumns = std::size_t{1} << 24;

Eigen::AlignedBox2d bounds_of(const octomap::OcTree* tree, const std::vector<Pose>& path) {
  Eigen::AlignedBox2d bounds;  // empty
  if (tree != nullptr && tree->size() > 0) {
    double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
    tree->getMetricMin(x0, y0, z0);
    tree->getMetricMax(x1, y1, z1);
    bounds.extend(Eigen::Vector2d(x0, y0));
    bounds.extend(Eigen::Vector2d(x1, y1));
  }
  for (const Pose& pose : path) bounds.extend(pose.position.head<2>());
  if (bounds.isEmpty()) bounds.extend(Eigen::Vector2d::Zero());
  return bounds;
}

// Per map column (x-y cell): how many occupied cells it holds, and whether any cell is free.
struct ColumnGrid {
  double x0 = 0.0;
  double y0 = 0.0;
  double cell = 1.0;
  int nx = 0;
  int ny = 0;
  std::vector<std::uint32_t> occupied;
  std::vector<std::uint8_t> free;

  std::size_t index(int ix, int iy) const {
    return static_cast<std::size_t>(iy) * static_cast<std::size_t>(nx) +
           static_cast<std::size_t>(ix);
  }
  void add(double x, double y, bool is_occupied, std::uint32_t cells) {
    const int ix = static_cast<int>(std::floor((x - x0) / cell));
    const int iy = static_cast<int>(std::floor((y - y0) / cell));
    if (ix < 0 || iy < 0 || ix >= nx || iy >= ny) return;
    if (is_occupied) {
      occupied[index(ix, iy)] += cells;
    } else {
      free[index(ix, iy)] = 1;
    }
  }
};

ColumnGrid columns_of(const octomap::OcTree& tree) {
  ColumnGrid grid;
  double z0 = 0, z1 = 0, x1 = 0, y1 = 0;
  tree.getMetricMin(grid.x0, grid.y0, z0);
  tree.getMetricMax(x1, y1, z1);
  const double resolution = tree.getResolution();
  grid.cell = resolution;
  auto cells_across = [&](double extent) {
    return std::max(1, static_cast<int>(std::ceil(extent / grid.cell - 1e-6)));
  };
  while (true) {
    grid.nx = cells_across(x1 - grid.x0);
    grid.ny = cells_across(y1 - grid.y0);
    if (static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny) <= kMaxColumns) break;
    grid.cell *= 2.0;
  }
  grid.occupied.assign(static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny), 0);
  grid.free.assign(grid.occupied.size(), 0);
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    // A pruned leaf stands for n x n x n cells: n columns across each way, n cells high.
    const double size = it.getSize();
    const int n = std::max(1, static_cast<int>(std::lround(size / resolution)));
    const bool is_occupied = tree.isNodeOccupied(*it);
    const double left = it.getX() - size / 2.0;
    const double bottom = it.getY() - size / 2.0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        grid.add(left + (i + 0.5) * resolution, bottom + (j + 0.5) * resolution, is_occupied,
                 static_cast<std::uint32_t>(n));
      }
    }
  }
  return grid;
}

// Per pixel: the fullest column drawn on it, and whether a free column is.
struct PixelColumns {
  std::vector<std::uint32_t> occupied;
  std::vector<std::uint8_t> free;
};

// Every column paints the pixels its footprint touches (at least one), so a wall one cell thick
// stays visible when a pixel is wider than a cell.
PixelColumns rasterise(const ColumnGrid& grid, const TopDownView& view) {
  PixelColumns pixels;
  const std::size_t count =
      static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height);
  pixels.occupied.assign(count, 0);
  pixels.free.assign(count, 0);
  const double ppm = view.pixels_per_metre;
  auto span = [](double from, double to, int& begin, int& end) {
    begin = static_cast<int>(std::floor(from + 1e-9));
    end = std::max(begin + 1, static_cast<int>(std::ceil(to - 1e-9)));
  };
  for (int iy = 0; iy < grid.ny; ++iy) {
    for (int ix = 0; ix < grid.nx; ++ix) {
      const std::size_t c = grid.index(ix, iy);
      if (grid.occupied[c] == 0 && grid.free[c] == 0) continue;
      const double wx = grid.x0 + ix * grid.cell;
      const double wy = grid.y0 + iy * grid.cell;
      int col_begin = 0, col_end = 0, row_begin = 0, row_end = 0;
      span(view.margin_px + (wx - view.min_x) * ppm,
           view.margin_px + (wx + grid.cell - view.min_x) * ppm, col_begin, col_end);
      span(view.margin_px + (view.max_y - wy - grid.cell) * ppm,
           view.margin_px + (view.max_y - wy) * ppm, row_begin, row_end);
      for (int row = std::max(0, row_begin); row < std::min(view.height, row_end); ++row) {
        for (int col = std::max(0, col_begin); col < std::min(view.width, col_end); ++col) {
          const std::size_t p =
              static_cast<std::size_t>(row) * static_cast<std::size_t>(view.width) +
              static_cast<std::size_t>(col);
          pixels.occupied[p] = std::max(pixels.occupied[p], grid.occupied[c]);
          pixels.free[p] |= grid.free[c];
        }
      }
    }
  }
  return pixels;
}

void draw_map(const octomap::OcTree& tree, const TopDownView& view, RgbImage& image) {
  if (tree.size() == 0) return;
  const PixelColumns pixels = rasterise(columns_of(tree), view);
  const std::uint32_t fullest = *std::max_element(pixels.occupied.begin(), pixels.occupied.end());
  for (int row = 0; row < view.height; ++row) {
    for (int col = 0; col < view.width; ++col) {
      const std::size_t p = static_cast<std::size_t>(row) * static_cast<std::size_t>(view.width) +
                            static_cast<std::size_t>(col);
      if (pixels.occupied[p] > 0) {
        const double fullness = static_cast<double>(pixels.occupied[p]) / fullest;
        const auto grey =
            static_cast<std::uint8_t>(std::lround(kLightestOccupied * (1.0 - fullness)));
        image.set(col, row, {grey, grey, grey});
      } else if (pixels.free[p] != 0) {
        image.set(col, row, kFree);
      }
    }
  }
}

void draw_disc(RgbImage& image, const Eigen::Vector2i& centre, int radius, Rgb colour) {
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      if (dx * dx + dy * dy <= radius * radius) image.set(centre.x() + dx, centre.y() + dy, colour);
    }
  }
}

// Bresenham's line, each step stamped with a small square for a visible width.
void draw_segment(RgbImage& image, Eigen::Vector2i from, const Eigen::Vector2i& to, Rgb colour) {
  const int dx = std::abs(to.x() - from.x());
  const int dy = -std::abs(to.y() - from.y());
  const int sx = from.x() < to.x() ? 1 : -1;
  const int sy = from.y() < to.y() ? 1 : -1;
  int error = dx + dy;
  while (true) {
    for (int oy = -kPathHalfWidthPx; oy <= kPathHalfWidthPx; ++oy) {
      for (int ox = -kPathHalfWidthPx; ox <= kPathHalfWidthPx; ++ox) {
        image.set(from.x() + ox, from.y() + oy, colour);
      }
    }
    if (from == to) break;
    const int twice = 2 * error;
    if (twice >= dy) {
      error += dy;
      from.x() += sx;
    }
    if (twice <= dx) {
      error += dx;
      from.y() += sy;
    }
  }
}

void draw_path(const std::vector<Pose>& path, const TopDownView& view, RgbImage& image) {
  if (path.empty()) return;
  auto pixel = [&](const Pose& p) { return view.pixel_of(p.position.x(), p.position.y()); };
  for (std::size_t i = 1; i < path.size(); ++i) {
    draw_segment(image, pixel(path[i - 1]), pixel(path[i]), kPath);
  }
  draw_disc(image, pixel(path.back()), kMarkerRadiusPx + 1, kBlack);
  draw_disc(image, pixel(path.back()), kMarkerRadiusPx, kEnd);
  draw_disc(image, pixel(path.front()), kMarkerRadiusPx + 1, kBlack);
  draw_disc(image, pixel(path.front()), kMarkerRadiusPx, kStart);
}

// 1, 2 or 5 times a power of ten: the longest such length within a fifth of the drawn width.
double scale_bar_length(const TopDownView& view) {
  const double target = 0.2 * (view.width - 2 * view.margin_px) / view.pixels_per_metre;
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  for (double step : {5.0, 2.0, 1.0}) {
    if (step * decade <= target) return step * decade;
  }
  return decade;
}

void draw_scale_bar(double length_m, const TopDownView& view, RgbImage& image) {
  const int left = view.margin_px;
  const int right = left + static_cast<int>(std::lround(length_m * view.pixels_per_metre));
  const int row = view.height - std::max(1, view.margin_px / 2);
  for (int col = left; col <= right; ++col) {
    for (int r = row - 1; r <= row + 1; ++r) image.set(col, r, kBlack);
  }
  for (int r = row - 5; r <= row + 5; ++r) {
    image.set(left, r, kBlack);
    image.set(right, r, kBlack);
  }
}

}  // namespace

Eigen::Vector2i TopDownView::pixel_of(double x, double y) const {
  return {margin_px + static_cast<int>(std::floor((x - min_x) * pixels_per_metre)),
          margin_px + static_cast<int>(std::floor((max_y - y) * pixels_per_metre))};
}

TopDownView fit_view(const Eigen::AlignedBox2d& bounds, const TopDownStyle& style) {
  Eigen::AlignedBox2d box = bounds;
  const Eigen::Vector2d centre = box.center();
  const Eigen::Vector2d half = (box.sizes() / 2.0).cwiseMax(0.5);
  box = Eigen::AlignedBox2d(centre - half, centre + half);
  TopDownView view;
  view.min_x = box.min().x();
  view.max_y = box.max().y();
  view.margin_px = style.margin_px;
  view.pixels_per_metre =
      std::min(style.max_pixels_per_metre, style.max_side_px / box.sizes().maxCoeff());
  view.width = 2 * style.margin_px +
               std::max(1, static_cast<int>(std::ceil(box.sizes().x() * view.pixels_per_metre)));
  view.height = 2 * style.margin_px +
                std::max(1, static_cast<int>(std::ceil(box.sizes().y() * view.pixels_per_metre)));
  return view;
}

TopDownMap render_top_down(const octomap::OcTree* tree, const std::vector<Pose>& path,
                           const TopDownStyle& style) {
  const TopDownView view = fit_view(bounds_of(tree, path), style);
  TopDownMap map{RgbImage(view.width, view.height), view, scale_bar_length(view)};
  if (tree != nullptr) draw_map(*tree, view, map.image);
  draw_path(path, view, map.image);
  draw_scale_bar(map.scale_bar_m, view, map.image);
  return map;
}

}  // namespace uavslam::io
