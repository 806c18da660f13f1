#include "eval/Consistency.hpp"

#include <Eigen/Cholesky>

namespace uavslam::eval {

std::optional<Nees> nees(const Vec3& error, const Eigen::Matrix3d& covariance) {
  std::vector<int> axes;
  for (int i = 0; i < 3; ++i) {
    if (covariance(i, i) > 0.0) axes.push_back(i);
  }
  if (axes.empty()) return std::nullopt;
  const auto n = static_cast<Eigen::Index>(axes.size());
  Eigen::MatrixXd block(n, n);
  Eigen::VectorXd e(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    e(r) = error(axes[static_cast<std::size_t>(r)]);
    for (Eigen::Index c = 0; c < n; ++c) {
      block(r, c) =
          covariance(axes[static_cast<std::size_t>(r)], axes[static_cast<std::size_t>(c)]);
    }
  }
  const Eigen::LLT<Eigen::MatrixXd> cholesky(block);
  if (cholesky.info() != Eigen::Success) return std::nullopt;
  return Nees{e.dot(cholesky.solve(e)), static_cast<int>(n)};
}

NeesSummary summarize(const std::vector<Nees>& samples) {
  NeesSummary s;
  s.count = samples.size();
  if (samples.empty()) return s;
  for (const Nees& n : samples) {
    s.mean += n.value;
    s.mean_dimension += n.dimension;
  }
  s.mean /= static_cast<double>(s.count);
  s.mean_dimension /= static_cast<double>(s.count);
  return s;
}

}  // namespace uavslam::eval
