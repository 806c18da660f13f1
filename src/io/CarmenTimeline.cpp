#include "io/CarmenTimeline.hpp"

#include <algorithm>
#include <cmath>

namespace uavslam::io {

double CarmenTimeline::next(double ipc_timestamp) {
  const double stamp =
      std::isfinite(last_) ? std::max(last_ + kStep, ipc_timestamp) : ipc_timestamp;
  adjusted_ += stamp != ipc_timestamp;
  last_ = stamp;
  return stamp;
}

}  // namespace uavslam::io
