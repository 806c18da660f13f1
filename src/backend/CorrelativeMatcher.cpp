#include "backend/CorrelativeMatcher.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>

#include <Eigen/Geometry>

#include "core/Angles.hpp"

namespace uavslam::backend {

// ---- the likelihood field --------------------------------------------------------------------

// Each point raises the cells within 3 sigma of it to exp(-d^2 / (2 sigma^2)), d from the cell's
// centre (a blurred occupancy grid, Olson 2009). The Gaussian is separable, exp(-(dx^2 + dy^2) /
// (2 sigma^2)) = exp(-dx^2 / (2 sigma^2)) exp(-dy^2 / (2 sigma^2)): 2 (2r + 1) exp per point, not
// (2r + 1)^2.
LikelihoodField::LikelihoodField(const std::vector<Eigen::Vector2d>& points, double resolution,
                                 double hit_sigma)
    : resolution_(resolution) {
  if (!(resolution > 0) || !std::isfinite(resolution))
    throw std::invalid_argument("CorrelativeMatcher: the resolution must be positive");
  std::vector<Eigen::Vector2d> finite;
  finite.reserve(points.size());
  for (const auto& p : points)
    if (p.allFinite()) finite.push_back(p);
  if (finite.empty()) return;
  Eigen::Vector2d lo = finite.front(), hi = finite.front();
  for (const auto& p : finite) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const int reach = hit_sigma > 0 ? static_cast<int>(std::ceil(3.0 * hit_sigma / resolution_)) : 0;
  origin_ = lo - Eigen::Vector2d::Constant((reach + 1) * resolution_);
  const Eigen::Vector2i top = cell_of(hi);
  width_ = top.x() + reach + 2;
  height_ = top.y() + reach + 2;
  cells_.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0.0f);
  const int span = 2 * reach + 1;
  std::vector<double> gx(static_cast<std::size_t>(span)), gy(gx.size());
  const auto gauss = [&](int cell, double origin, double p) {
    const double d = origin + (cell + 0.5) * resolution_ - p;
    return hit_sigma > 0 ? std::exp(-(d * d) / (2 * hit_sigma * hit_sigma)) : 1.0;
  };
  for (const auto& p : finite) {
    const Eigen::Vector2i c = cell_of(p);
    for (int k = 0; k < span; ++k) {
      gx[static_cast<std::size_t>(k)] = gauss(c.x() - reach + k, origin_.x(), p.x());
      gy[static_cast<std::size_t>(k)] = gauss(c.y() - reach + k, origin_.y(), p.y());
    }
    for (int k = 0; k < span; ++k) {
      float* row =
          cells_.data() + static_cast<std::size_t>(c.y() - reach + k) * width_ + (c.x() - reach);
      const double wy = gy[static_cast<std::size_t>(k)];
      for (int i = 0; i < span; ++i)
        row[i] = std::max(row[i], static_cast<float>(gx[static_cast<std::size_t>(i)] * wy));
    }
  }
}

float LikelihoodField::value(int ix, int iy) const {
  if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return 0.0f;
  return cells_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(width_) +
                static_cast<std::size_t>(ix)];
}

// ---- branch-and-bound ----------------------------------------------------------------------

namespace {

// The max-pyramid (Hess 2016 eq. 14) over the rectangle of field cells [x0, x0 + width) x
// [y0, y0 + height): level h at (i, j) holds the largest field value over
// [i, i + 2^h) x [j, j + 2^h) within the rectangle. All levels share one layout, so a cell has
// the same index at every level.
class Pyramid {
 public:
  Pyramid(const LikelihoodField& field, int x0, int y0, int width, int height, int levels)
      : width_(width),
        height_(height),
        size_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)),
        cells_(size_ * static_cast<std::size_t>(levels), 0.0f) {
    // The field's cells in rectangle coordinates: where level 0 is not 0.
    const auto within = [](long long v, int n) {
      return static_cast<int>(std::clamp(v, 0LL, static_cast<long long>(n)));
    };
    const int fx0 = within(-static_cast<long long>(x0), width);
    const int fx1 = within(static_cast<long long>(field.width()) - x0, width);
    const int fy0 = within(-static_cast<long long>(y0), height);
    const int fy1 = within(static_cast<long long>(field.height()) - y0, height);
    if (fx0 >= fx1 || fy0 >= fy1) return;  // all 0
    for (int v = fy0; v < fy1; ++v)
      std::copy_n(field.row(y0 + v) + (x0 + fx0), fx1 - fx0, at(0, v) + fx0);
    // Level h from level h-1, step = 2^(h-1): the max over [i, i + 2^h) is the larger of those
    // over [i, i + step) and [i + step, i + 2^h), along x into `rows`, then along y. Level h is
    // 0 outside [f0 - 2^h + 1, f1): only that part is computed.
    std::vector<float> rows(size_, 0.0f);
    for (int h = 1; h < levels; ++h) {
      const int step = 1 << (h - 1);
      const int xa = std::max(0, fx0 - (2 * step - 1));
      const int ya = std::max(0, fy0 - (2 * step - 1));
      const int ya_finer = std::max(0, fy0 - (step - 1));
      const int xs = std::max(xa, std::min(fx1, width - step));  // [xa, xs): x + step inside
      for (int v = ya_finer; v < fy1; ++v) {
        const float* f = at(h - 1, v);
        float* r = rows.data() + static_cast<std::size_t>(v) * width;
        for (int u = xa; u < xs; ++u) r[u] = std::max(f[u], f[u + step]);
        for (int u = xs; u < fx1; ++u) r[u] = f[u];
      }
      for (int v = ya; v < fy1; ++v) {
        const float* r = rows.data() + static_cast<std::size_t>(v) * width;
        float* l = at(h, v);
        if (v + step < height) {
          const float* r2 = r + static_cast<std::size_t>(step) * width;
          for (int u = xa; u < fx1; ++u) l[u] = std::max(r[u], r2[u]);
        } else {
          std::copy(r + xa, r + fx1, l + xa);
        }
      }
    }
  }

  const float* level(int h) const { return cells_.data() + static_cast<std::size_t>(h) * size_; }
  int width() const { return width_; }

 private:
  float* at(int h, int v) {
    return cells_.data() + static_cast<std::size_t>(h) * size_ +
           static_cast<std::size_t>(v) * static_cast<std::size_t>(width_);
  }

  int width_;
  int height_;
  std::size_t size_;
  std::vector<float> cells_;
};

// One yaw of the window: the scan turned by it and moved to the window's centre, as indices into
// a pyramid level (offsets[begin, end)); translating it by (dx, dy) cells adds dy * width + dx
// to every index (Hess 2016 sec. V-A).
struct Rotation {
  double yaw = 0.0;
  std::size_t begin = 0;
  std::size_t end = 0;
};

// A set of poses: one yaw, translations [dx, dx + 2^level) x [dy, dy + 2^level) in cells from the
// window's centre, with an upper bound of their scores (a leaf, level 0: its score).
struct Candidate {
  int rotation = 0;
  int dx = 0;
  int dy = 0;
  int level = 0;
  double bound = 0.0;
  std::size_t rest = 0;  // where BranchAndBound keeps its sums past each block of points
};

// The poses near the best one, which the search for a look-alike skips.
struct Exclusion {
  Candidate best;
  double radius_cells = 0.0;
  double angle = 0.0;
};

class BranchAndBound {
 public:
  BranchAndBound(const Pyramid& pyramid, const std::vector<Rotation>& rotations,
                 const std::vector<std::int32_t>& offsets, std::size_t scan_size, int reach,
                 int top)
      : pyramid_(pyramid),
        rotations_(rotations),
        offsets_(offsets),
        scan_size_(static_cast<double>(scan_size)),
        reach_(reach),
        top_(top),
        block_(std::max<std::size_t>(4, ((scan_size + kChecks - 1) / kChecks + 3) / 4 * 4)),
        blocks_((scan_size + block_ - 1) / block_) {
    const std::size_t per_axis = static_cast<std::size_t>(2 * reach_ / (1 << top_) + 1);
    const std::size_t roots = rotations_.size() * per_axis * per_axis;
    rests_.reserve((roots + 4 * static_cast<std::size_t>(top_ + 1)) * blocks_);
  }

  // Hess 2016 Algorithm 3: depth-first from the coarsest level, the most promising child first,
  // pruning every node whose bound cannot beat the best leaf so far (at first: a leaf must score
  // at least `floor`, or more when `strict`). The leaves whose score was computed go to `leaves`.
  std::optional<Candidate> run(double floor, bool strict, const std::optional<Exclusion>& exclusion,
                               std::vector<Candidate>* leaves) {
    floor_ = floor;
    strict_ = strict;
    exclusion_ = exclusion;
    leaves_ = leaves;
    best_.reset();
    rests_.clear();
    std::vector<Candidate> roots;
    roots.reserve(rests_.capacity() / blocks_);
    for (int r = 0; r < static_cast<int>(rotations_.size()); ++r)
      for (int dx = -reach_; dx <= reach_; dx += 1 << top_)
        for (int dy = -reach_; dy <= reach_; dy += 1 << top_) {
          Candidate c{r, dx, dy, top_, 0.0};
          if (add(c, nullptr)) roots.push_back(c);
        }
    std::sort(roots.begin(), roots.end(),
              [](const Candidate& a, const Candidate& b) { return a.bound > b.bound; });
    for (const Candidate& c : roots) {
      if (!improves(c.bound)) break;  // sorted: no later one can improve either
      descend(c);
    }
    return best_;
  }

  bool excluded_by(const Candidate& c, const Exclusion& e) const {
    const double yaw = rotations_[static_cast<std::size_t>(c.rotation)].yaw -
                       rotations_[static_cast<std::size_t>(e.best.rotation)].yaw;
    if (std::abs(wrap_angle(yaw)) >= e.angle) return false;
    const int last = (1 << c.level) - 1;  // the node's farthest translation from the best
    const double fx = std::max(std::abs(c.dx - e.best.dx), std::abs(c.dx + last - e.best.dx));
    const double fy = std::max(std::abs(c.dy - e.best.dy), std::abs(c.dy + last - e.best.dy));
    return std::hypot(fx, fy) < e.radius_cells;
  }

  std::size_t scored() const { return scored_; }

 private:
  void descend(const Candidate& c) {
    if (c.level == 0) {
      best_ = c;
      return;
    }
    const std::size_t mark = rests_.size();
    std::array<Candidate, 4> children;  // the four quarters (Hess 2016 eq. 16)
    std::size_t n = 0;
    const int half = 1 << (c.level - 1);
    for (int ox : {0, half})
      for (int oy : {0, half}) {
        Candidate child{c.rotation, c.dx + ox, c.dy + oy, c.level - 1, 0.0};
        if (add(child, &c)) children[n++] = child;
      }
    for (std::size_t i = 1; i < n; ++i)  // by bound, largest first
      for (std::size_t j = i; j > 0 && children[j].bound > children[j - 1].bound; --j)
        std::swap(children[j], children[j - 1]);
    for (std::size_t i = 0; i < n; ++i) {
      if (!improves(children[i].bound)) break;
      descend(children[i]);
    }
    rests_.resize(mark);
  }

  bool improves(double bound) const {
    if (best_) return bound > best_->bound;
    return strict_ ? bound > floor_ : bound >= floor_;
  }

  // Scores `c` (a child of `parent`, or a root) unless it starts outside the window or lies
  // wholly near the best pose; true, keeping its sums in rests_, when it may improve on the best
  // so far (the bar only rises: one that cannot now never will).
  bool add(Candidate& c, const Candidate* parent) {
    if (c.dx > reach_ || c.dy > reach_ || (exclusion_ && excluded_by(c, *exclusion_))) return false;
    ++scored_;
    // The sum a node needs (less a margin far above rounding): below it, it is pruned.
    const double bar = best_ ? best_->bound : floor_;
    const double need = (bar - 1e-9) * scan_size_;
    c.rest = rests_.size();
    rests_.resize(c.rest + blocks_);
    const bool kept = bound(c, need, parent) && improves(c.bound);
    if (c.level == 0 && kept && leaves_) leaves_->push_back(c);
    if (!kept) rests_.resize(c.rest);
    return kept;
  }

  // The mean of level-h values at the scan's cells (Hess 2016 eq. 15): each is the largest of the
  // level-0 values over the node's translations, so the mean bounds each of their scores. Every
  // node of a rotation sums in the same order, so a child's sum never exceeds its parent's, nor
  // its sum over any points the parent's over them. False (c.bound unset) when the sum so far
  // plus the most the rest can add (the parent's sum over them; a root's: 1 per point) falls
  // short of `need`.
  bool bound(Candidate& c, double need, const Candidate* parent) {
    const Rotation& r = rotations_[static_cast<std::size_t>(c.rotation)];
    const std::int32_t* off = offsets_.data() + r.begin;
    const std::size_t n = r.end - r.begin;
    const float* level = pyramid_.level(c.level);
    const std::ptrdiff_t base = static_cast<std::ptrdiff_t>(c.dy) * pyramid_.width() + c.dx;
    const double* most = parent ? rests_.data() + parent->rest : nullptr;
    double* rest = rests_.data() + c.rest;  // the sums so far, then the sums past each block
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;  // four sums: no chain of dependent adds
    std::size_t i = 0, b = 0;
    while (i < n) {
      const std::size_t stop = std::min(n, i + block_);
      for (; i + 4 <= stop; i += 4) {
        s0 += level[base + off[i]];
        s1 += level[base + off[i + 1]];
        s2 += level[base + off[i + 2]];
        s3 += level[base + off[i + 3]];
      }
      for (; i < stop; ++i) s0 += level[base + off[i]];
      const double sum = (s0 + s1) + (s2 + s3);
      if (sum + (most ? most[b] : static_cast<double>(n - i)) < need) return false;
      rest[b++] = sum;
    }
    const double sum = (s0 + s1) + (s2 + s3);
    for (std::size_t k = 0; k < b; ++k) rest[k] = sum - rest[k];
    c.bound = sum / scan_size_;
    return true;
  }

  static constexpr std::size_t kChecks = 8;  // of a node's sum against `need`, at most

  const Pyramid& pyramid_;
  const std::vector<Rotation>& rotations_;
  const std::vector<std::int32_t>& offsets_;
  double scan_size_;
  int reach_;
  int top_;
  double floor_ = 0.0;
  bool strict_ = false;
  std::optional<Exclusion> exclusion_;
  std::vector<Candidate>* leaves_ = nullptr;
  std::size_t block_;          // points between checks, a multiple of 4
  std::size_t blocks_;         // checks
  std::vector<double> rests_;  // a stack: the roots', then each level's kept children's
  std::optional<Candidate> best_;
  std::size_t scored_ = 0;
};

}  // namespace

// ---- the matcher ---------------------------------------------------------------------------

CorrelativeMatcher::CorrelativeMatcher(const std::vector<Eigen::Vector2d>& reference,
                                       const CorrelativeMatcherConfig& config)
    : config_(config), grid_(reference, config.resolution, config.hit_sigma) {
  if (config.levels < 1 || config.levels > 16)
    throw std::invalid_argument("CorrelativeMatcher: levels must be 1..16");
}

// Hess 2016 eq. 7: the yaw step that moves the scan's farthest point by about one cell.
double CorrelativeMatcher::angular_step(const std::vector<Eigen::Vector2d>& scan) const {
  if (config_.angular_step > 0) return config_.angular_step;
  double d_max = 0.0;
  for (const auto& p : scan) d_max = std::max(d_max, p.norm());
  if (d_max <= 0) return kPi;
  const double r = config_.resolution;
  return std::acos(std::clamp(1.0 - r * r / (2 * d_max * d_max), -1.0, 1.0));
}

double CorrelativeMatcher::score(const std::vector<Eigen::Vector2d>& scan,
                                 const Eigen::Vector3d& pose) const {
  if (scan.empty()) return 0.0;
  const Eigen::Matrix2d turn = Eigen::Rotation2Dd(pose.z()).toRotationMatrix();
  double sum = 0.0;
  for (const auto& p : scan) {
    const Eigen::Vector2i c = grid_.cell_of(turn * p + pose.head<2>());
    sum += grid_.value(c.x(), c.y());
  }
  return sum / static_cast<double>(scan.size());
}

bool CorrelativeMatcher::is_peak(const std::vector<Eigen::Vector2d>& scan,
                                 const Eigen::Vector3d& pose) const {
  const double at = score(scan, pose);
  const Eigen::Vector3d steps(config_.resolution, config_.resolution, angular_step(scan));
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {-1.0, 1.0}) {
      Eigen::Vector3d neighbour = pose;
      neighbour[axis] += sign * steps[axis];
      if (score(scan, neighbour) > at) return false;
    }
  }
  return true;
}

CorrelativeMatch CorrelativeMatcher::match(const std::vector<Eigen::Vector2d>& scan,
                                           const SearchWindow& window, double min_score) const {
  CorrelativeMatch result;
  if (scan.empty() || !window.centre.allFinite() || !std::isfinite(window.linear) ||
      !std::isfinite(window.angular))
    return result;
  for (const auto& p : scan)
    if (!p.allFinite()) return result;
  const double step = angular_step(scan);
  const double cells = std::clamp(window.linear / config_.resolution, 0.0, 1e6);
  const int reach = static_cast<int>(std::floor(cells + 1e-9));
  const int top = config_.levels - 1;

  // The yaws centre +- k * step within the window.
  const double half_width = std::clamp(window.angular, 0.0, kPi);
  const int k_max = static_cast<int>(std::floor(std::min(half_width / step, 1e6) + 1e-9));
  std::vector<Rotation> rotations;
  std::vector<Eigen::Matrix2d> turns;
  for (int k = -k_max; k <= k_max; ++k) {
    Rotation r;
    r.yaw = window.centre.z() + k * step;
    rotations.push_back(r);
    turns.push_back(Eigen::Rotation2Dd(r.yaw).toRotationMatrix());
  }
  // The cells the points can land on: within each turned bounding box of the scan (+-1 cell for
  // rounding), and on the field or within `reach` of it (a point farther off scores 0 at every
  // pose of the window: it is left out, adding 0 changes no sum).
  Eigen::Vector2d box_lo = scan.front(), box_hi = scan.front();
  for (const auto& p : scan) {
    box_lo = box_lo.cwiseMin(p);
    box_hi = box_hi.cwiseMax(p);
  }
  Eigen::Vector2i lo = Eigen::Vector2i::Constant(std::numeric_limits<int>::max());
  Eigen::Vector2i hi = Eigen::Vector2i::Constant(std::numeric_limits<int>::min());
  for (const Eigen::Matrix2d& turn : turns)
    for (double x : {box_lo.x(), box_hi.x()})
      for (double y : {box_lo.y(), box_hi.y()}) {
        const Eigen::Vector2i c =
            grid_.cell_of(turn * Eigen::Vector2d(x, y) + window.centre.head<2>());
        lo = lo.cwiseMin(c - Eigen::Vector2i::Ones());
        hi = hi.cwiseMax(c + Eigen::Vector2i::Ones());
      }
  lo = lo.cwiseMax(Eigen::Vector2i::Constant(-reach));
  hi = hi.cwiseMin(Eigen::Vector2i(grid_.width(), grid_.height()) +
                   Eigen::Vector2i::Constant(reach - 1));
  const bool none = (lo.array() > hi.array()).any();  // no point lands on the field
  if (none) lo = hi = Eigen::Vector2i::Zero();
  // The pyramid over the cells the search looks up, [lo - reach, hi + reach] (a node's bound
  // looks up its first translation's cells), and the points' cells as indices into it.
  const Eigen::Vector2i corner = lo - Eigen::Vector2i::Constant(reach);
  const int width = hi.x() - lo.x() + 2 * reach + 1;
  const int height = hi.y() - lo.y() + 2 * reach + 1;
  if (static_cast<long long>(width) * height > std::numeric_limits<std::int32_t>::max())
    throw std::length_error("CorrelativeMatcher: the search window is too large");
  const Pyramid pyramid(grid_, corner.x(), corner.y(), width, height, top + 1);
  std::vector<std::int32_t> offsets;
  offsets.reserve(rotations.size() * scan.size());
  for (std::size_t k = 0; k < rotations.size(); ++k) {
    rotations[k].begin = offsets.size();
    for (const auto& p : scan) {
      const Eigen::Vector2i c = grid_.cell_of(turns[k] * p + window.centre.head<2>());
      if (!none && (c.array() >= lo.array()).all() && (c.array() <= hi.array()).all())
        offsets.push_back((c.y() - corner.y()) * width + (c.x() - corner.x()));
    }
    rotations[k].end = offsets.size();
  }

  BranchAndBound search(pyramid, rotations, offsets, scan.size(), reach, top);
  std::vector<Candidate> leaves;
  const auto best = search.run(min_score, false, std::nullopt, &leaves);
  if (best) {
    result.found = true;
    result.score = best->bound;
    result.pose << window.centre.x() + best->dx * config_.resolution,
        window.centre.y() + best->dy * config_.resolution,
        wrap_angle(rotations[static_cast<std::size_t>(best->rotation)].yaw);
    // The look-alike: the best of the poses far from the best one. The search starts from the
    // best such leaf the first search scored (exact: only a better one can replace it), else
    // from a score of 0.
    const Exclusion nearby{*best, config_.ambiguity_radius / config_.resolution,
                           config_.ambiguity_angle};
    std::optional<double> seed;
    for (const Candidate& leaf : leaves)
      if (!search.excluded_by(leaf, nearby) && (!seed || leaf.bound > *seed)) seed = leaf.bound;
    const auto second = search.run(seed.value_or(0.0), seed.has_value(), nearby, nullptr);
    if (second)
      result.second_score = second->bound;
    else if (seed)
      result.second_score = *seed;
  }
  result.candidates_scored = search.scored();
  return result;
}

}  // namespace uavslam::backend
