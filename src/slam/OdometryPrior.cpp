#include "slam/OdometryPrior.hpp"

namespace uavslam {

OdometryPrior::OdometryPrior(double max_gap, std::size_t capacity) : buffer_(max_gap, capacity) {}

Vec3 OdometryPrior::motion_to(double t) {
  const std::optional<Vec3> now = buffer_.position_at(t);
  if (!now || !last_posed_) {
    ++without_prior_;
    return Vec3::Zero();
  }
  ++with_prior_;
  return *now - *last_posed_;
}

void OdometryPrior::scan_posed(double t) {
  last_posed_ = buffer_.position_at(t);
}

}  // namespace uavslam
