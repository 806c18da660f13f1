// Where the scans have seen through (beyond the seed): what moves. A person walking beside or
// ahead of the vehicle is a surface the ICP locks onto like any other, and one walking at the
// vehicle's pace holds it still: in a corridor whose walls leave the axis free, the match then
// says the vehicle stands while it drives on. The scans themselves tell what moves: a place their
// beams passed through before anything was seen in it was empty then, so what is seen there now
// came there (the way an occupancy grid's misses clear what a hit once put in a cell, as
// Cartographer's probability grid does).
//
// A grid of the horizontal plane, `resolution` m cells, remembers per cell how many beams crossed
// it before its first return and since its last, and in how many scans (over how long) it held
// one. It is of one slab of the building, the scanner's height give or take 0.3 m: a UAV's tilted
// beam that strikes a table top below, under space its level beams crossed, is not in it (tried: a
// grid of cubes, with each height its own, took a person first seen at a new height, as the
// vehicle climbed, for something that stood there). A cell whose first sight was a return, or
// that held returns for half a second, is a surface; one crossed `min_passes` times before its
// first return was empty space, and so is one crossed again and again since its last (what stood
// there left). A point in a cell seen empty lately (`memory` s), with nothing that stood there
// from the first within `margin` of it (the ICP's pairing gate: a wall that the pose's error puts
// into the free cells in front of it still has its cells there), moved there: nothing that stays
// put lies there to pair it with. Beams mark free space up to `reach` m (an angular error of a
// degree moves a far return by more than a cell), and not over their last stretch.
//
// The grid lives in the map's frame as the poses placed it; when the map is moved (a loop closed,
// the heading anchored) what it saw lately moves with the vehicle.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/ScanProjection.hpp"
#include "core/Types.hpp"

namespace uavslam {

class FreeSpace {
 public:
  FreeSpace(double resolution, double reach, int min_passes, double memory, double margin);

  // One scan's beams, taken at `stamp` (s), from `sensor` to each of `returns` (world frame; their
  // horizontal parts, those in the scanner's slab).
  void add_scan(double stamp, const Vec3& sensor, const Points& returns);

  // The point, in the last scan's slab, lies where the beams saw empty space within the last
  // `memory` s (of the last scan added), and nothing that stood there from the first lies within
  // the margin.
  bool moved_there(const Vec3& point) const;

  // The map moved (a loop closed, the heading anchored): `moved` takes the old frame to the new.
  // What the beams saw lately moves with it, each cell to where the move takes its centre (the
  // vehicle's recent poses move with its current one); what they saw longer ago is forgotten.
  void move(const Eigen::Isometry3d& moved);

  void clear();

 private:
  // Per cell: beams that crossed it before its first return and since its last, the scans with a
  // return in it (all saturating; a cell crossed often enough since its last return is empty
  // again: the first two start over), the last such scan's number; when a beam last crossed it,
  // and when it held its first return (since it was last empty) and its last.
  struct Cell {
    std::uint8_t passes_before_return = 0;
    std::uint16_t passes_since_return = 0;
    std::uint8_t scans_returned = 0;
    std::uint32_t last_scan = 0;
    float last_pass = 0.0f;  // s after the first scan
    float first_return = 0.0f;
    float last_return = 0.0f;
  };
  bool surface(const Cell& c) const;
  bool seen_empty(const Cell& c) const;
  bool recent(const Cell& c) const;
  static void merge(Cell& into, const Cell& c);
  static constexpr int kChunkBits = 6;  // 64 x 64 cells a chunk
  static constexpr int kChunk = 1 << kChunkBits;
  using Chunk = std::array<Cell, kChunk * kChunk>;

  static std::size_t cell_index(std::int64_t ix, std::int64_t iy);  // within its chunk
  std::int64_t index(double coordinate) const;
  Cell& cell(std::int64_t ix, std::int64_t iy);
  const Cell* find(std::int64_t ix, std::int64_t iy) const;
  bool standing_near(std::int64_t ix, std::int64_t iy) const;
  bool in_slab(const Vec3& point) const;
  void pass(std::int64_t ix, std::int64_t iy);
  void mark_return(const Eigen::Vector2d& point);
  void trace(const Eigen::Vector2d& from, const Eigen::Vector2d& to);

  double resolution_;
  double reach_;
  int min_passes_;
  double memory_;
  int margin_cells_;
  std::uint32_t scans_ = 0;
  double first_stamp_ = 0.0;
  float now_ = 0.0f;            // the last scan's stamp, s after the first
  double sensor_height_ = 0.0;  // the last scan's
  std::unordered_map<std::uint64_t, Chunk> chunks_;
  // The chunks last written and read: a beam's cells and a point's neighbours mostly share one
  // (the map's nodes stay put as it grows).
  std::uint64_t written_key_ = 0;
  Chunk* written_ = nullptr;
  mutable std::uint64_t read_key_ = 0;
  mutable const Chunk* read_ = nullptr;
};

// The points of `scan` from its level beams. A floor or ceiling beam's point (a UAV's down-looking
// beams) is what measures the vehicle's height, never a thing that moves.
Points level_points(const ProjectedScan& scan);

// Which of the points of `scan` (placed with the body at `position`, turned by `yaw` about it)
// moved there: those in free space, or all of a small object with several such; never a floor or
// ceiling beam's.
std::vector<bool> moved_points(const ProjectedScan& scan, const Vec3& position, double yaw,
                               const FreeSpace& free_space);

// Removes from `scan` the moved_points and returns how many.
std::size_t set_aside_moving(ProjectedScan& scan, const Vec3& position, double yaw,
                             const FreeSpace& free_space);

}  // namespace uavslam
