#include "core/extensions/PriorAgreement.hpp"

#include <cmath>

namespace uavslam {

PriorDistance distance_from_prior(const Vec3& correction, const Eigen::Matrix3d& observed,
                                  const Eigen::Matrix3d& innovation_covariance) {
  const Eigen::Matrix<double, 3, Eigen::Dynamic> basis = observed_basis(observed);
  if (basis.cols() == 0) return {};
  const int directions = static_cast<int>(basis.cols());
  const Eigen::MatrixXd S = basis.transpose() * innovation_covariance * basis;
  const Eigen::VectorXd nu = basis.transpose() * correction;
  const Eigen::LDLT<Eigen::MatrixXd> solver(S);
  if (solver.info() != Eigen::Success || !(solver.vectorD().array() > 0.0).all()) {
    // No spread at all: any correction disagrees.
    return {nu.isZero() ? 0.0 : INFINITY, directions};
  }
  return {std::sqrt(nu.dot(solver.solve(nu))), directions};
}

PriorGate::Verdict PriorGate::judge(const PriorDistance& distance, const Vec3& correction,
                                    const Eigen::Matrix3d& observed,
                                    const Eigen::Matrix3d& match_covariance) {
  if (sigmas_ <= 0.0 || distance.sigmas <= sigmas_) {
    run_ = 0;
    return Verdict::Agrees;
  }
  // Two matches' corrections differ by their two errors: the covariance is twice the match's.
  const bool continues =
      run_ > 0 &&
      distance_from_prior(correction - last_correction_, observed, 2.0 * match_covariance).sigmas <=
          sigmas_;
  run_ = continues ? run_ + 1 : 1;
  last_correction_ = correction;
  if (overrule_ > 0 && run_ > overrule_) {
    run_ = 0;
    return Verdict::Overrules;
  }
  return Verdict::Rejected;
}

}  // namespace uavslam
