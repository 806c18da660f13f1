#include "core/extensions/HeadingDrift.hpp"

#include <algorithm>

namespace uavslam {

void HeadingDrift::add_check(double disagreement) {
  if (last_) {
    sum_ += disagreement * *last_;
    ++count_;
  }
  last_ = disagreement;
}

double HeadingDrift::variance_per_keyframe() const {
  return count_ > 0 ? std::max(0.0, sum_ / double(count_)) : 0.0;
}

}  // namespace uavslam
