// The loop search of the back end (issue 18): a correlative scan matcher (Olson 2009) with
// branch-and-bound over x, y and yaw on a precomputed grid pyramid (Hess, Kohler, Rapp, Andor
// 2016, "Real-Time Loop Closure in 2D LIDAR SLAM", sec. V). It finds where a new keyframe's scan
// lies among an older keyframe's points without trusting the current pose estimate: the best pose
// in a search window, exact with respect to an exhaustive search over the same discretisation,
// and the best look-alike far from it, to reject ambiguous matches (a corridor of equal doors).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace uavslam::backend {

struct CorrelativeMatcherConfig {
  double resolution = 0.05;   // m, the finest grid's cell
  double hit_sigma = 0.05;    // m, how far a reference point spreads over the grid
  int levels = 7;             // of the pyramid: level h holds maxima over 2^h x 2^h cells
  double angular_step = 0.0;  // rad; 0 = from the scan's farthest point (Hess 2016 eq. 7)
  // A hypothesis is a look-alike (counts for second_score) when its translation is at least
  // ambiguity_radius from the best one's or its yaw at least ambiguity_angle from the best one's.
  double ambiguity_radius = 0.5;  // m
  double ambiguity_angle = 0.3;   // rad
};

// Where to search: the poses (x, y, yaw) within `linear` of the centre in x and in y and within
// `angular` in yaw, on the discretisation (cells of `resolution`, the angular step).
struct SearchWindow {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // x, y (m), yaw (rad)
  double linear = 1.0;                               // m, half-width in x and in y
  double angular = 0.5;                              // rad, half-width
};

struct CorrelativeMatch {
  bool found = false;  // a pose scored at least min_score
  // x, y, yaw of the scan's frame in the reference's frame (where the scan's points land on the
  // reference's: p_ref = R(yaw) p_scan + (x, y)).
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();
  double score = 0.0;                 // mean grid value at the scan's points at `pose`, 0..1
  double second_score = 0.0;          // the best look-alike's score (0 if none, or if not found)
  std::size_t candidates_scored = 0;  // nodes of the search whose bound was computed (both passes)
};

// The reference points on a grid of values 0..1, the likelihood field: at each cell the largest
// exp(-d^2 / (2 hit_sigma^2)) over the points, d from the cell's centre (Olson 2009). Outside: 0.
// match() builds its max-pyramid (Hess 2016 eq. 14) over the cells the search can reach.
class LikelihoodField {
 public:
  // Non-finite points are left out; hit_sigma <= 0 marks only the points' own cells (value 1).
  // Throws std::invalid_argument for a resolution that is not positive.
  LikelihoodField(const std::vector<Eigen::Vector2d>& points, double resolution, double hit_sigma);

  // The cell holding `point` (may be outside the grid).
  Eigen::Vector2i cell_of(const Eigen::Vector2d& point) const {
    return {index_of((point.x() - origin_.x()) / resolution_),
            index_of((point.y() - origin_.y()) / resolution_)};
  }
  float value(int ix, int iy) const;
  int width() const { return width_; }
  int height() const { return height_; }
  const float* row(int iy) const { return cells_.data() + static_cast<std::size_t>(iy) * width_; }
  double resolution() const { return resolution_; }

 private:
  // floor(scaled), clamped far outside any grid, where int arithmetic on cells cannot overflow
  // (inline: std::floor may be a library call).
  static int index_of(double scaled) {
    const double v = std::min(std::max(scaled, -1e9), 1e9);
    const int t = static_cast<int>(v);  // towards 0
    return t - (v < t ? 1 : 0);
  }

  double resolution_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();  // corner of cell (0, 0)
  int width_ = 0;
  int height_ = 0;
  std::vector<float> cells_;  // row-major, width * height
};

class CorrelativeMatcher {
 public:
  // `reference`: the older keyframe's points in its own frame (the grid spans their bounding box:
  // keep them to one keyframe's range). Throws std::invalid_argument for a resolution that is not
  // positive or levels outside 1..16. Builds the finest grid only: match() builds the pyramid over
  // the cells its window can reach.
  CorrelativeMatcher(const std::vector<Eigen::Vector2d>& reference,
                     const CorrelativeMatcherConfig& config);

  // The best pose in the window scoring at least min_score, found by branch-and-bound (Hess 2016
  // Algorithm 3), exact with respect to scoring every pose of the window's discretisation; then
  // the best look-alike by a second branch-and-bound that skips the poses near the best one. The
  // cost grows with the scan's size: subsample it to about the grid's resolution first. An empty
  // scan, a non-finite point or a non-finite window finds nothing.
  CorrelativeMatch match(const std::vector<Eigen::Vector2d>& scan, const SearchWindow& window,
                         double min_score) const;

  // The score of one pose: the mean finest-grid value at the cells of the scan's points.
  double score(const std::vector<Eigen::Vector2d>& scan, const Eigen::Vector3d& pose) const;
  // Whether `pose` is a peak of the score: no pose a step from it (a cell in x or in y, the
  // angular step in yaw), inside the window searched or beyond it, scores higher. The best pose of
  // a window is a peak within it, but one on the window's rim whose score still rises past it is
  // the slope of a ridge (a corridor's walls overlapping more as one scan slides along the other)
  // or of a peak the window does not hold: no loop.
  bool is_peak(const std::vector<Eigen::Vector2d>& scan, const Eigen::Vector3d& pose) const;
  // The yaw step match() uses for this scan: the configured one, or Hess 2016 eq. 7.
  double angular_step(const std::vector<Eigen::Vector2d>& scan) const;
  const CorrelativeMatcherConfig& config() const { return config_; }

 private:
  CorrelativeMatcherConfig config_;
  LikelihoodField grid_;
};

}  // namespace uavslam::backend
