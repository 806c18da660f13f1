// Occupancy maps as files: OctoMap's own binary format (.bt, which octovis and the octomap tools
// open) and the centres of the occupied cells as a point cloud.
#pragma once

#include <memory>
#include <string>

#include <octomap/OcTree.h>

#include "core/Types.hpp"
#include "io/FileError.hpp"

namespace uavslam::io {

// Writes the tree with OcTree::writeBinaryConst (maximum likelihood: each known cell occupied or
// free). Throws FileError "<path>: cannot open for writing: <reason>" or "<path>: cannot write".
void write_bt(const std::string& path, const octomap::OcTree& tree);

// Reads a .bt file. Throws FileError "<path>: ..." for a missing or undecodable file.
std::unique_ptr<octomap::OcTree> read_bt(const std::string& path);

// The centre of every occupied cell at the tree's resolution: a pruned leaf of size 2^k cells
// yields all (2^k)^3 cells it stands for, so the cloud does not depend on how the tree was pruned.
Points occupied_cell_centres(const octomap::OcTree& tree);

}  // namespace uavslam::io
