#include "eval/TrajectoryMetrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "eval/TrajectoryAssociation.hpp"

namespace uavslam::eval {
namespace {

constexpr double kRadiansToDegrees = 180.0 / EIGEN_PI;

std::string describe_stamps(const char* side, const std::vector<Pose>& poses) {
  if (poses.empty()) return std::string(side) + " has no poses";
  const auto [first, last] = std::minmax_element(
      poses.begin(), poses.end(), [](const Pose& a, const Pose& b) { return a.stamp < b.stamp; });
  char text[160];
  std::snprintf(text, sizeof text, "%s has %zu poses, stamps %.3f .. %.3f s", side, poses.size(),
                first->stamp, last->stamp);
  return text;
}

void require_two_pairs(const std::vector<PosePair>& pairs, const std::vector<Pose>& estimate,
                       const std::vector<Pose>& ground_truth, double max_time_difference) {
  if (pairs.size() >= 2) return;
  char within[64];
  std::snprintf(within, sizeof within, "%g s", max_time_difference);
  throw std::invalid_argument("compare_trajectories: only " + std::to_string(pairs.size()) +
                              " estimate poses have a ground-truth pose within " + within +
                              ", need at least 2 (" + describe_stamps("estimate", estimate) + "; " +
                              describe_stamps("ground truth", ground_truth) + ")");
}

void require_positive_delta(double rpe_delta) {
  if (rpe_delta > 0.0) return;
  throw std::invalid_argument("compare_trajectories: rpe_delta must be > 0 s, got " +
                              std::to_string(rpe_delta));
}

// ATE (Sturm et al. 2012, eq. 8): the RMSE over all pairs of the translation of
// Q_i^-1 S P_i, which for the positions is |p_i - q_i| once S has aligned the estimate.
void absolute_trajectory_error(const std::vector<PosePair>& pairs, TrajectoryErrors& errors) {
  double sum_squared = 0.0, sum_horizontal = 0.0, sum_vertical = 0.0, sum = 0.0, max = 0.0;
  for (const PosePair& pair : pairs) {
    const Vec3 difference = pair.estimate.position - pair.ground_truth.position;
    sum_squared += difference.squaredNorm();
    sum_horizontal += difference.head<2>().squaredNorm();
    sum_vertical += difference.z() * difference.z();
    sum += difference.norm();
    max = std::max(max, difference.norm());
  }
  const auto n = static_cast<double>(pairs.size());
  errors.ate_rmse = std::sqrt(sum_squared / n);
  errors.ate_mean = sum / n;
  errors.ate_max = max;
  errors.ate_horizontal_rmse = std::sqrt(sum_horizontal / n);
  errors.ate_vertical_rmse = std::sqrt(sum_vertical / n);
  errors.final_position_error =
      (pairs.back().estimate.position - pairs.back().ground_truth.position).norm();
}

// For pair i, the later pair whose stamp is closest to t_i + delta, chosen from the first one at
// least delta later and the one before it; none once no pair is delta later (the tail).
std::size_t rpe_partner(const std::vector<PosePair>& pairs, std::size_t i, double delta) {
  const double target = pairs[i].estimate.stamp + delta;
  const auto first_reaching =
      std::lower_bound(pairs.begin() + static_cast<std::ptrdiff_t>(i) + 1, pairs.end(), target,
                       [](const PosePair& pair, double t) { return pair.estimate.stamp < t; });
  const auto j = static_cast<std::size_t>(first_reaching - pairs.begin());
  if (j == pairs.size()) return j;
  const bool previous_is_closer =
      j - 1 > i && target - pairs[j - 1].estimate.stamp < pairs[j].estimate.stamp - target;
  return previous_is_closer ? j - 1 : j;
}

// The angle of a rotation, robust near zero where acos(w) loses precision.
double rotation_angle(const Eigen::Quaterniond& q) {
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

// RPE (Sturm et al. 2012, eq. 1-3): E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j) with Q ground truth and
// P estimate; RMSE of E's translation and of E's rotation angle over all pairs (i, j).
void relative_pose_error(const std::vector<PosePair>& pairs, double delta,
                         TrajectoryErrors& errors) {
  double sum_translation = 0.0, sum_rotation = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i + 1 < pairs.size(); ++i) {
    const std::size_t j = rpe_partner(pairs, i, delta);
    if (j == pairs.size()) break;  // later i reach no further
    const Eigen::Isometry3d truth_motion =
        pairs[i].ground_truth.isometry().inverse() * pairs[j].ground_truth.isometry();
    const Eigen::Isometry3d estimate_motion =
        pairs[i].estimate.isometry().inverse() * pairs[j].estimate.isometry();
    const Eigen::Isometry3d error = truth_motion.inverse() * estimate_motion;
    sum_translation += error.translation().squaredNorm();
    const double angle = rotation_angle(Eigen::Quaterniond(error.linear()));
    sum_rotation += angle * angle;
    ++count;
  }
  errors.rpe_delta = delta;
  errors.rpe_pairs = count;
  if (count == 0) {
    errors.rpe_translation_rmse = std::numeric_limits<double>::quiet_NaN();
    errors.rpe_rotation_rmse_deg = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const auto n = static_cast<double>(count);
  errors.rpe_translation_rmse = std::sqrt(sum_translation / n);
  errors.rpe_rotation_rmse_deg = std::sqrt(sum_rotation / n) * kRadiansToDegrees;
}

}  // namespace

TrajectoryErrors compare_trajectories(const std::vector<Pose>& estimate,
                                      const std::vector<Pose>& ground_truth,
                                      const MetricOptions& options) {
  require_positive_delta(options.rpe_delta);
  std::vector<PosePair> pairs =
      associate_by_stamp(estimate, ground_truth, options.max_time_difference);
  require_two_pairs(pairs, estimate, ground_truth, options.max_time_difference);
  align_estimates(pairs, estimate_alignment(pairs, options.alignment));
  TrajectoryErrors errors;
  errors.pairs = pairs.size();
  absolute_trajectory_error(pairs, errors);
  relative_pose_error(pairs, options.rpe_delta, errors);
  return errors;
}

}  // namespace uavslam::eval
