// Trajectories in the TUM RGB-D benchmark format (Sturm et al. 2012), as evo reads and writes
// them: one pose per line, "t x y z qx qy qz qw" separated by spaces, '#' starts a comment.
#pragma once

#include <string>
#include <vector>

#include "core/Types.hpp"
#include "io/FileError.hpp"

namespace uavslam::io {

// Writes one line per pose: stamp with %.9f, position with %.6f, quaternion with %.9f.
// Throws FileError naming the path and the system's reason when the file cannot be written.
void write_tum(const std::string& path, const std::vector<Pose>& poses);

// Reads every pose line in file order; blank and comment lines are skipped, quaternions are
// normalised. Throws FileError "<path>:<line>: <problem>: '<text>'" on a line that is not 8 finite
// numbers or has a zero quaternion, and "<path>: cannot open: <reason>" on an unreadable file.
std::vector<Pose> read_tum(const std::string& path);

}  // namespace uavslam::io
