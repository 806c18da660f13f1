#include "io/OctreeFile.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

namespace uavslam::io {

void write_bt(const std::string& path, const octomap::OcTree& tree) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw file_error(path, std::string("cannot open for writing: ") + std::strerror(errno));
  if (!tree.writeBinaryConst(out) || !out.flush()) throw file_error(path, "cannot write");
}

std::unique_ptr<octomap::OcTree> read_bt(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw file_error(path, std::string("cannot open: ") + std::strerror(errno));
  // The resolution is read from the file's header; 0.1 is only the placeholder until then.
  auto tree = std::make_unique<octomap::OcTree>(0.1);
  if (!tree->readBinary(in)) throw file_error(path, "not an OctoMap binary tree (.bt)");
  return tree;
}

Points occupied_cell_centres(const octomap::OcTree& tree) {
  Points centres;
  const double resolution = tree.getResolution();
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const double size = it.getSize();
    const int cells = std::max(1, static_cast<int>(std::lround(size / resolution)));
    const Vec3 corner = Vec3(it.getX(), it.getY(), it.getZ()) - Vec3::Constant(size / 2.0);
    for (int i = 0; i < cells; ++i) {
      for (int j = 0; j < cells; ++j) {
        for (int k = 0; k < cells; ++k) {
          centres.push_back(corner + (Vec3(i, j, k) + Vec3::Constant(0.5)) * resolution);
        }
      }
    }
  }
  return centres;
}

}  // namespace uavslam::io
