// A ground robot's wheel odometry from its true path: what a CARMEN log's ODOM lines and scan
// messages carry (uavslam simulate --carmen). Each step between two true poses, in the body
// frame of the first (forward d, sideways s, turn a), is read by the wheels as
//   d' = (1 + e_t) d + n_d,  s' = (1 + e_t) s + n_s,  a' = (1 + e_r) a + n_a,
//   n_d, n_s ~ N(0, k_t^2 |(d, s)|),  n_a ~ N(0, k_r^2 |a| + k_rt^2 |(d, s)|),
// (scale errors e, random-walk noise k: the variance grows with the motion, so the sampling rate
// does not change it) and integrated from the first true pose, each step from the heading it
// started at (the frame it is measured in).
#pragma once

#include <cstdint>
#include <vector>

#include "core/PlanarPose.hpp"
#include "core/Types.hpp"
#include "sim/Scenario.hpp"

namespace uavslam::sim {

// One odometry pose per true pose, the first equal to it. The same seed gives the same poses.
std::vector<PlanarPose> wheel_odometry(const std::vector<Pose>& truth,
                                       const WheelOdometrySpec& spec, std::uint64_t seed);

}  // namespace uavslam::sim
