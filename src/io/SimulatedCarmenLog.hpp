// A simulated ground robot's run written as a Freiburg-style benchmark log: the CARMEN log of its
// planar scanner and wheel odometry (sim/WheelOdometry) and the relations of its true path
// (eval/TruthRelations), for `uavslam run --carmen` and `uavslam eval --relations` as they are
// used on the real logs: buildings the real logs do not show.
#pragma once

#include <string>
#include <vector>

#include "core/Types.hpp"
#include "sim/Scenario.hpp"

namespace uavslam::io {

struct SimulatedCarmenFiles {
  std::size_t scans = 0;
  std::size_t relations = 0;
  double path_length = 0.0;  // m, of the true path
};

// One ODOM line and one ROBOTLASER1 line per scan (the odometry at the scan's stamp), then the
// relations file. `truth`: the true body pose at each scan's stamp. Throws std::invalid_argument
// for a scanner that is not planar (beams out of the sensor's x-y plane or unevenly spaced, a
// mount that is not level) and FileError when a file cannot be written.
SimulatedCarmenFiles write_simulated_carmen_log(const std::string& log_path,
                                                const std::string& relations_path,
                                                const sim::Scenario& scenario,
                                                const std::vector<Scan>& scans,
                                                const std::vector<Pose>& truth);

}  // namespace uavslam::io
