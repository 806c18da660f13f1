// A picture of an occupancy map seen from above, with the flight path over it: what the ground
// station shows an operator after (or during) a flight.
//
// Each map column (one cell across, all heights) is drawn darker the more occupied cells it holds
// (a wall floor to ceiling is black, a low box mid grey), columns seen only free are light grey,
// unknown space is white. The path is a blue polyline with a green start and a red end disc; a
// black bar in the bottom-left margin shows scale_bar_m metres. North (+y) is up, +x to the right.
#pragma once

#include <vector>

#include <octomap/OcTree.h>
#include <Eigen/Geometry>

#include "core/Types.hpp"
#include "io/RgbImage.hpp"

namespace uavslam::io {

struct TopDownStyle {
  int max_side_px = 1200;               // the longer side of the drawn area (margins excluded)
  int margin_px = 30;                   // white border around the map bounds
  double max_pixels_per_metre = 200.0;  // small maps are not blown up further
};

// Where a world x-y point lands in the picture.
struct TopDownView {
  double min_x = 0.0;  // world x at the left edge of the drawn area
  double max_y = 0.0;  // world y at its top edge
  double pixels_per_metre = 1.0;
  int margin_px = 0;
  int width = 1;  // of the whole image, margins included
  int height = 1;

  // The pixel (column, row) containing the world point.
  Eigen::Vector2i pixel_of(double x, double y) const;
};

// The scale and image size that fit `bounds` (world x-y, metres) into the style's size. Bounds
// narrower than 1 m are widened to 1 m around their centre.
TopDownView fit_view(const Eigen::AlignedBox2d& bounds, const TopDownStyle& style);

struct TopDownMap {
  RgbImage image;
  TopDownView view;
  double scale_bar_m = 0.0;  // length of the scale bar
};

// The picture of `tree` (may be null: only the path) and `path`, fitted to the known space of the
// tree and the path together. With neither, a 1 m square around the origin.
TopDownMap render_top_down(const octomap::OcTree* tree, const std::vector<Pose>& path,
                           const TopDownStyle& style = {});

}  // namespace uavslam::io
