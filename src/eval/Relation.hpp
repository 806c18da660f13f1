// The inputs of the Freiburg SLAM benchmark (Kümmerle et al. 2009): planar pose estimates stamped
// with the scans' ipc_timestamps, and the true relative motions between pairs of those scans.
// Plain values only, so that the file readers in io can produce them without linking eval.
#pragma once

namespace uavslam::eval {

// A planar pose of the robot at the ipc_timestamp of one scan (m, m, rad).
struct PlanarStamped {
  double t = 0.0;
  double x = 0.0, y = 0.0, theta = 0.0;
};

// The true motion from the pose at scan time t1 to the pose at scan time t2, expressed in the
// frame of the pose at t1 (m, m, rad). The relation files' z, roll and pitch are 0 in 2D.
struct Relation {
  double t1 = 0.0, t2 = 0.0;
  double x = 0.0, y = 0.0, yaw = 0.0;
};

}  // namespace uavslam::eval
