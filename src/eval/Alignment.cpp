#include "eval/Alignment.hpp"

#include <Eigen/Geometry>

namespace uavslam::eval {

Eigen::Isometry3d estimate_alignment(const std::vector<PosePair>& pairs, Alignment alignment) {
  if (alignment == Alignment::None || pairs.empty()) return Eigen::Isometry3d::Identity();
  Eigen::Matrix3Xd estimated(3, pairs.size());
  Eigen::Matrix3Xd truth(3, pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    estimated.col(static_cast<Eigen::Index>(i)) = pairs[i].estimate.position;
    truth.col(static_cast<Eigen::Index>(i)) = pairs[i].ground_truth.position;
  }
  const Eigen::Matrix4d transform = Eigen::umeyama(estimated, truth, /*with_scaling=*/false);
  return Eigen::Isometry3d(transform);
}

void align_estimates(std::vector<PosePair>& pairs, const Eigen::Isometry3d& estimate_to_truth) {
  const Eigen::Quaterniond rotation(estimate_to_truth.linear());
  for (PosePair& pair : pairs) {
    pair.estimate.position = estimate_to_truth * pair.estimate.position;
    pair.estimate.orientation = (rotation * pair.estimate.orientation).normalized();
  }
}

}  // namespace uavslam::eval
