// How far an estimated trajectory is from the ground truth: the absolute trajectory error (ATE)
// and the relative pose error (RPE) of Sturm et al., "A Benchmark for the Evaluation of RGB-D
// SLAM Systems", IROS 2012 (the TUM RGB-D benchmark; evo's evo_ape / evo_rpe).
#pragma once

#include <cstddef>
#include <vector>

#include "core/Types.hpp"
#include "eval/Alignment.hpp"

namespace uavslam::eval {

struct MetricOptions {
  double max_time_difference = 0.01;  // s; pairs estimate and ground truth (associate_by_stamp)
  Alignment alignment = Alignment::None;
  double rpe_delta = 1.0;  // s; the time span of the RPE's pose pairs
};

struct TrajectoryErrors {
  std::size_t pairs = 0;  // associated estimate/ground-truth poses

  // ATE: position differences after alignment, in m.
  double ate_rmse = 0.0;
  double ate_mean = 0.0;
  double ate_max = 0.0;
  double ate_horizontal_rmse = 0.0;  // of the x-y part
  double ate_vertical_rmse = 0.0;    // of the z part

  // RPE over pose pairs about rpe_delta seconds apart; NaN when no pair spans rpe_delta.
  double rpe_translation_rmse = 0.0;   // m
  double rpe_rotation_rmse_deg = 0.0;  // degrees
  double rpe_delta = 0.0;              // s, the option used
  std::size_t rpe_pairs = 0;           // pose pairs the RPE was taken over

  double final_position_error = 0.0;  // m, at the last associated stamp, after alignment
};

// Associates the trajectories by stamp, aligns the estimate as asked and computes the errors.
// Throws std::invalid_argument if fewer than 2 poses associate (the message gives each side's
// pose count and time range) or rpe_delta is not positive.
TrajectoryErrors compare_trajectories(const std::vector<Pose>& estimate,
                                      const std::vector<Pose>& ground_truth,
                                      const MetricOptions& options = {});

}  // namespace uavslam::eval
