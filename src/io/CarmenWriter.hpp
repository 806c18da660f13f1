// Writes CARMEN logs (.clf) as CarmenLog.hpp reads them: a simulated ground robot's log
// (uavslam simulate --carmen) for the same tools as the Freiburg logs. Scans are written as
// ROBOTLASER1 messages, whose start angle, resolution and maximum range are explicit, so any
// planar beam layout survives; a range that is no return (not finite, or at least max_range) is
// written as max_range. Ranges to the millimetre, poses and stamps to six decimals.
#pragma once

#include <string>
#include <vector>

#include "io/CarmenLog.hpp"

namespace uavslam::io {

// `comments` first (each as a "# " line), then the messages in the order given.
// Throws FileError naming the path and the system's reason when it cannot be written.
void write_carmen_log(const std::string& path, const std::vector<std::string>& comments,
                      const std::vector<CarmenMessage>& messages);

}  // namespace uavslam::io
