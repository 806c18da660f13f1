#include "core/extensions/FreeSpace.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/Heading.hpp"

namespace uavslam {

namespace {

// Scans with a return in a cell, and the time they span (s), that make it a surface however it
// was first seen. A person walking by holds a cell for as long as their body takes to pass it, a
// few tenths of a second at walking pace: a 10 Hz scanner sees that in a scan or two, a 40 Hz one
// in several (a wall stays).
constexpr std::uint8_t kSurfaceScans = 5;
constexpr float kSurfaceSeconds = 0.5f;

// A beam frees the space up to a share of its range, and at least a distance (m), short of its
// return: a beam that grazes a wall runs along it, through the cells in front of the surface, for
// its last cell / sin(angle to the wall) metres: in a corridor, a wall w m to the side is met r m
// away at sin(angle) = w / r, so that is r x cell / w: a tenth of the range for 0.1 m cells and a
// wall 1 m to the side.
constexpr double kShortOfReturnShare = 0.1;
constexpr double kShortOfReturn = 0.5;

// Crossings of a cell after its last return, per scan that saw something in it, that empty it
// again (Cartographer's grids weigh one hit as five misses).
constexpr int kPassesPerReturn = 5;

// The slab of the building the grid is of: within this height (m) of the scanner. Its level beams
// stay in it as the vehicle tilts a few degrees (0.2 m at 4 m and 3 degrees); a tilted beam that
// strikes a table top below, under space the level beams crossed, is left out (a 2D log's beams
// all lie in it).
constexpr double kSlab = 0.3;

// Moved points that make a small object one that moved: a person 10 m away is three beams of 1
// degree.
constexpr std::size_t kMinMovedPoints = 3;

// An object ends where the next point is farther than this from the last (m, and m per m of
// range: at a few beams' spacing a surface seen obliquely stays one object).
constexpr double kObjectGap = 0.1;
constexpr double kObjectGapPerMetre = 0.05;
// m across at most: a person, two side by side, a cart. A longer surface seen in free space is a
// wall the pose placed a little off, or a door: matched as ever.
constexpr double kMaxMovingObject = 1.2;

std::uint64_t chunk_key(std::int64_t cx, std::int64_t cy) {
  return (static_cast<std::uint64_t>(cx) << 32) ^ (static_cast<std::uint64_t>(cy) & 0xffffffffu);
}

}  // namespace

FreeSpace::FreeSpace(double resolution, double reach, int min_passes, double memory, double margin)
    : resolution_(resolution),
      reach_(reach),
      min_passes_(std::clamp(min_passes, 1, 255)),
      memory_(memory),
      margin_cells_(static_cast<int>(std::ceil(margin / resolution))) {}

std::size_t FreeSpace::cell_index(std::int64_t ix, std::int64_t iy) {
  return static_cast<std::size_t>(((iy & (kChunk - 1)) << kChunkBits) + (ix & (kChunk - 1)));
}

std::int64_t FreeSpace::index(double coordinate) const {
  return static_cast<std::int64_t>(std::floor(coordinate / resolution_));
}

bool FreeSpace::recent(const Cell& c) const {
  const bool passed = c.passes_before_return > 0 || c.passes_since_return > 0;
  return (passed && now_ - c.last_pass <= memory_) ||
         (c.scans_returned > 0 && now_ - c.last_return <= memory_);
}

// Two cells the move brought onto one: what either saw.
void FreeSpace::merge(Cell& into, const Cell& c) {
  const bool returned = into.scans_returned > 0;
  into.passes_before_return = std::max(into.passes_before_return, c.passes_before_return);
  into.passes_since_return = std::max(into.passes_since_return, c.passes_since_return);
  into.scans_returned = std::max(into.scans_returned, c.scans_returned);
  into.last_scan = std::max(into.last_scan, c.last_scan);
  into.last_pass = std::max(into.last_pass, c.last_pass);
  if (c.scans_returned > 0) {
    into.first_return = returned ? std::min(into.first_return, c.first_return) : c.first_return;
  }
  into.last_return = std::max(into.last_return, c.last_return);
}

void FreeSpace::move(const Eigen::Isometry3d& moved) {
  std::unordered_map<std::uint64_t, Chunk> before = std::move(chunks_);
  clear();
  for (const auto& [key, chunk] : before) {
    const std::int64_t cx = static_cast<std::int32_t>(key >> 32);
    const std::int64_t cy = static_cast<std::int32_t>(key & 0xffffffffu);
    for (std::size_t i = 0; i < chunk.size(); ++i) {
      if (!recent(chunk[i])) continue;
      const auto ix = static_cast<std::int64_t>(cx * kChunk + std::int64_t(i % kChunk));
      const auto iy = static_cast<std::int64_t>(cy * kChunk + std::int64_t(i / kChunk));
      const Vec3 to =
          moved * Vec3((double(ix) + 0.5) * resolution_, (double(iy) + 0.5) * resolution_, 0.0);
      merge(cell(index(to.x()), index(to.y())), chunk[i]);
    }
  }
}

void FreeSpace::clear() {
  chunks_.clear();
  written_ = nullptr;
  read_ = nullptr;
}

FreeSpace::Cell& FreeSpace::cell(std::int64_t ix, std::int64_t iy) {
  const std::uint64_t key = chunk_key(ix >> kChunkBits, iy >> kChunkBits);
  if (written_ == nullptr || key != written_key_) {
    written_ = &chunks_[key];
    written_key_ = key;
  }
  return (*written_)[cell_index(ix, iy)];
}

const FreeSpace::Cell* FreeSpace::find(std::int64_t ix, std::int64_t iy) const {
  const std::uint64_t key = chunk_key(ix >> kChunkBits, iy >> kChunkBits);
  if (read_ == nullptr || key != read_key_) {
    const auto found = chunks_.find(key);
    if (found == chunks_.end()) return nullptr;
    read_ = &found->second;
    read_key_ = key;
  }
  return &(*read_)[cell_index(ix, iy)];
}

void FreeSpace::pass(std::int64_t ix, std::int64_t iy) {
  Cell& c = cell(ix, iy);
  c.last_pass = now_;
  if (c.scans_returned == 0) {
    if (c.passes_before_return < 255) ++c.passes_before_return;
    return;
  }
  // Crossed again and again since its last return, several times for each scan that saw something
  // in it: what was there has gone, and the cell is empty space again (what comes next is judged
  // afresh). A thin thing in the cell (a chair's leg) is seen scan after scan while the beams
  // beside it cross the cell a few times in between.
  if (c.passes_since_return < 65535) ++c.passes_since_return;
  const int vacated = std::max(min_passes_, kPassesPerReturn * std::min<int>(c.scans_returned, 50));
  if (c.passes_since_return >= vacated) {
    c.passes_before_return = static_cast<std::uint8_t>(std::min<int>(c.passes_since_return, 255));
    c.passes_since_return = 0;
    c.scans_returned = 0;
  }
}

void FreeSpace::mark_return(const Eigen::Vector2d& point) {
  Cell& c = cell(index(point.x()), index(point.y()));
  if (c.scans_returned == 0) c.first_return = now_;
  if (c.last_scan != scans_ && c.scans_returned < 255) ++c.scans_returned;
  c.last_scan = scans_;
  c.last_return = now_;
  c.passes_since_return = 0;
}

// Every cell the segment crosses (Amanatides and Woo's traversal) is passed.
void FreeSpace::trace(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  const Eigen::Vector2d a = from / resolution_;
  const Eigen::Vector2d d = to / resolution_ - a;
  std::int64_t ix = index(from.x());
  std::int64_t iy = index(from.y());
  const std::int64_t end_x = index(to.x());
  const std::int64_t end_y = index(to.y());
  const int step_x = d.x() > 0.0 ? 1 : -1;
  const int step_y = d.y() > 0.0 ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // The segment's parameter (0 at from, 1 at to) at the next cell boundary on each axis.
  const double delta_x = d.x() != 0.0 ? std::abs(1.0 / d.x()) : kInf;
  const double delta_y = d.y() != 0.0 ? std::abs(1.0 / d.y()) : kInf;
  double next_x = d.x() != 0.0 ? (step_x > 0 ? (ix + 1 - a.x()) : (a.x() - ix)) * delta_x : kInf;
  double next_y = d.y() != 0.0 ? (step_y > 0 ? (iy + 1 - a.y()) : (a.y() - iy)) * delta_y : kInf;
  pass(ix, iy);
  while ((ix != end_x || iy != end_y) && std::min(next_x, next_y) <= 1.0) {
    if (next_x < next_y) {
      ix += step_x;
      next_x += delta_x;
    } else {
      iy += step_y;
      next_y += delta_y;
    }
    pass(ix, iy);
  }
}

void FreeSpace::add_scan(double stamp, const Vec3& sensor, const Points& returns) {
  if (scans_ == 0) first_stamp_ = stamp;
  ++scans_;
  now_ = static_cast<float>(stamp - first_stamp_);
  sensor_height_ = sensor.z();
  const Eigen::Vector2d from = sensor.head<2>();
  for (const Vec3& p : returns) {
    if (!in_slab(p)) continue;
    const Eigen::Vector2d to = p.head<2>();
    const double length = (to - from).norm();
    const double freed =
        std::min(length - std::max(kShortOfReturn, kShortOfReturnShare * length), reach_);
    if (freed > 0.0) trace(from, from + (to - from) * (freed / length));
    if (length <= reach_) mark_return(to);
  }
}

// A cell seen first holding a return, or holding returns for half a second: a wall's cell that
// grazing beams crossed before the first beam struck it is one; a person who walked through is
// not, nor a place a person stood and left (crossed since: empty again).
bool FreeSpace::surface(const Cell& c) const {
  return c.scans_returned > 0 &&
         (c.passes_before_return < min_passes_ ||
          (c.scans_returned >= kSurfaceScans && now_ - c.first_return >= kSurfaceSeconds));
}

// Crossed by beams before anything was seen in it; lately: the map's frame drifts, and a place
// seen empty a loop ago, seen again from the loop's end, is where its walls now appear.
bool FreeSpace::seen_empty(const Cell& c) const {
  return c.passes_before_return >= min_passes_ && now_ - c.last_pass <= memory_;
}

// Only what stood there when the beams first saw the place vouches for a point beside it: a thing
// that came and stayed (a person who paused, or the trail a fast scanner sees a walker leave) is
// a surface where it is, not a witness that its neighbour is a wall the pose placed a little off.
bool FreeSpace::standing_near(std::int64_t ix, std::int64_t iy) const {
  for (std::int64_t y = iy - margin_cells_; y <= iy + margin_cells_; ++y) {
    for (std::int64_t x = ix - margin_cells_; x <= ix + margin_cells_; ++x) {
      const Cell* c = find(x, y);
      if (c != nullptr && c->scans_returned > 0 && c->passes_before_return < min_passes_) {
        return true;
      }
    }
  }
  return false;
}

bool FreeSpace::in_slab(const Vec3& point) const {
  return std::abs(point.z() - sensor_height_) <= kSlab;
}

bool FreeSpace::moved_there(const Vec3& point) const {
  if (!in_slab(point)) return false;
  const std::int64_t ix = index(point.x());
  const std::int64_t iy = index(point.y());
  const Cell* c = find(ix, iy);
  if (c == nullptr || !seen_empty(*c) || surface(*c)) return false;
  return !standing_near(ix, iy);
}

Points level_points(const ProjectedScan& scan) {
  Points level;
  level.reserve(scan.points.size());
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (!scan.vertical[i]) level.push_back(scan.points[i]);
  }
  return level;
}

std::vector<bool> moved_points(const ProjectedScan& scan, const Vec3& position, double yaw,
                               const FreeSpace& free_space) {
  const Eigen::Matrix3d turn = yaw_rotation(yaw).toRotationMatrix();
  std::vector<bool> moved(scan.points.size());
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    moved[i] = !scan.vertical[i] && free_space.moved_there(position + turn * scan.points[i]);
  }
  // The scan cut into objects where the range jumps (beam order): a small object several of whose
  // points moved is a thing that moves, all of it (a person's back, walked into cells its body hid
  // from the beams, is seen nowhere empty); a larger one, or a lone point in free space (a wall's
  // edge, noise), stays.
  for (std::size_t begin = 0; begin < moved.size();) {
    std::size_t end = begin + 1;
    while (end < moved.size() && (scan.points[end] - scan.points[end - 1]).norm() <=
                                     kObjectGap + kObjectGapPerMetre * scan.points[end].norm()) {
      ++end;
    }
    const auto first = moved.begin() + std::ptrdiff_t(begin);
    const auto last = moved.begin() + std::ptrdiff_t(end);
    const bool small = (scan.points[end - 1] - scan.points[begin]).norm() <= kMaxMovingObject;
    const auto count = static_cast<std::size_t>(std::count(first, last, true));
    if (small && count >= kMinMovedPoints) {
      for (std::size_t i = begin; i < end; ++i) moved[i] = !scan.vertical[i];
    } else {
      std::fill(first, last, false);
    }
    begin = end;
  }
  return moved;
}

std::size_t set_aside_moving(ProjectedScan& scan, const Vec3& position, double yaw,
                             const FreeSpace& free_space) {
  const std::vector<bool> moved = moved_points(scan, position, yaw, free_space);
  return remove_points(scan, [&moved](std::size_t i) { return moved[i]; });
}

}  // namespace uavslam
