// Where a walking person (Scenario.hpp's Walker) is at a given time.
#pragma once

#include "sim/Scenario.hpp"

namespace uavslam::sim {

// The walker as a solid cylinder `t` s into the flight: `start + speed t` along its path and back,
// over and over (a path of length L is walked 0 -> L -> 0 in 2 L / speed s).
Cylinder walker_at(const Walker& walker, double t);

}  // namespace uavslam::sim
