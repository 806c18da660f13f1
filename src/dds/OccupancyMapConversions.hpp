// Between the `map` wire type (an OctoMap binary snapshot) and octomap::OcTree. Kept apart from
// Conversions.hpp so only the map server and the ground station pull in OctoMap.
#pragma once

#include <cstdint>
#include <memory>

#include <msg/OccupancyMap.h>
#include <octomap/OcTree.h>

#include "dds/Conversions.hpp"

namespace uavslam::dds {

// The tree's binary data as OcTree::writeBinaryData writes it (maximum likelihood: each known leaf
// occupied or free; no header, as octomap_msgs/Octomap carries it), with its resolution, the bounds
// of the known space and the count of occupied leaves. Prune the tree first for a compact snapshot.
msg::OccupancyMap to_msg(const octomap::OcTree& tree, std::uint64_t map_seq,
                         std::uint64_t map_points, double stamp, const Source& source);

// The tree a snapshot carries, at the snapshot's resolution. Throws DdsError "map snapshot
// <map_seq>: ..." when the resolution is not positive or the bytes are not exactly one tree.
std::unique_ptr<octomap::OcTree> octree_from_msg(const msg::OccupancyMap& message);

}  // namespace uavslam::dds
