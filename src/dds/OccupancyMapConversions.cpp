#include "dds/OccupancyMapConversions.hpp"

#include <sstream>
#include <string>

#include "dds/DdsError.hpp"

namespace uavslam::dds {
namespace {

msg::Vector3 to_msg_vector(double x, double y, double z) {
  msg::Vector3 v;
  v.x(x);
  v.y(y);
  v.z(z);
  return v;
}

std::uint64_t occupied_leaves(const octomap::OcTree& tree) {
  std::uint64_t count = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    count += tree.isNodeOccupied(*it);
  }
  return count;
}

}  // namespace

msg::OccupancyMap to_msg(const octomap::OcTree& tree, std::uint64_t map_seq,
                         std::uint64_t map_points, double stamp, const Source& source) {
  msg::OccupancyMap m;
  msg::Header header;
  header.stamp(to_msg_time(stamp));
  header.seq(map_seq);
  header.frame_id(source.frame_id);
  header.vehicle_id(source.vehicle_id);
  m.header(header);
  m.map_seq(map_seq);
  m.resolution(tree.getResolution());
  double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
  if (tree.size() > 0) {
    tree.getMetricMin(x0, y0, z0);
    tree.getMetricMax(x1, y1, z1);
  }
  m.min_bound(to_msg_vector(x0, y0, z0));
  m.max_bound(to_msg_vector(x1, y1, z1));
  m.occupied_cells(occupied_leaves(tree));
  m.map_points(map_points);
  std::ostringstream binary;
  tree.writeBinaryData(binary);
  const std::string bytes = binary.str();
  m.octomap_binary(std::vector<uint8_t>(bytes.begin(), bytes.end()));
  return m;
}

std::unique_ptr<octomap::OcTree> octree_from_msg(const msg::OccupancyMap& message) {
  const auto& bytes = message.octomap_binary();
  const std::string where = "map snapshot " + std::to_string(message.map_seq()) + ": ";
  if (!(message.resolution() > 0.0)) {
    throw DdsError(where + "resolution " + std::to_string(message.resolution()) + " m is not > 0");
  }
  std::istringstream binary(std::string(bytes.begin(), bytes.end()));
  auto tree = std::make_unique<octomap::OcTree>(message.resolution());
  if (!bytes.empty()) tree->readBinaryData(binary);
  // A short read means the bytes end before the tree does; leftovers mean they are not one tree.
  if (binary.fail() || binary.peek() != std::char_traits<char>::eof()) {
    throw DdsError(where + std::to_string(bytes.size()) +
                   " bytes do not decode as one OctoMap binary tree");
  }
  return tree;
}

}  // namespace uavslam::dds
