#include "core/extensions/PlanarCorrection.hpp"

#include <Eigen/Cholesky>
#include <cmath>

namespace uavslam {
namespace {

using Vec3x = Eigen::Vector3d;  // (t_x, t_y, yaw)

struct NormalEquations {
  Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
  Vec3x Jtr = Vec3x::Zero();

  void add(const Vec3x& J, double r, double w) {
    JtJ.noalias() += w * J * J.transpose();
    Jtr.noalias() += w * J * r;
  }
};

double cauchy_weight(double squared_residual, double scale) {
  return scale > 0.0 ? 1.0 / (1.0 + squared_residual / (scale * scale)) : 1.0;
}

NormalEquations horizontal_equations(const Correspondences& pairs, const Vec3& body,
                                     double robust_scale) {
  NormalEquations eq;
  for (std::size_t i = 0; i < pairs.scan.size(); ++i) {
    const Vec3 r = pairs.scan[i] - pairs.map[i];
    const Vec3 counted = counted_residual(pairs, i, r);
    const double w =
        pairs.weights[i].x() * cauchy_weight(counted.head<2>().squaredNorm(), robust_scale);
    if (w <= 0.0) continue;
    const Vec3 q = pairs.scan[i] - body;
    if (pairs.has_normal(i)) {
      const Vec3& n = pairs.normals[i];
      eq.add(Vec3x(n.x(), n.y(), -n.x() * q.y() + n.y() * q.x()), n.x() * r.x() + n.y() * r.y(), w);
    } else {
      eq.add(Vec3x(1.0, 0.0, -q.y()), r.x(), w);
      eq.add(Vec3x(0.0, 1.0, q.x()), r.y(), w);
    }
  }
  return eq;
}

double vertical_translation(const Correspondences& pairs) {
  double sum = 0.0;
  double weight = 0.0;
  for (std::size_t i = 0; i < pairs.scan.size(); ++i) {
    sum += pairs.weights[i].z() * (pairs.map[i].z() - pairs.scan[i].z());
    weight += pairs.weights[i].z();
  }
  return weight > 0.0 ? sum / weight : 0.0;
}

}  // namespace

PlanarCorrection best_correction(const Correspondences& pairs, const Vec3& body,
                                 const CorrectionOptions& options, const PlanarCorrection& so_far) {
  PlanarCorrection correction;
  correction.translation.z() = vertical_translation(pairs);
  NormalEquations eq = horizontal_equations(pairs, body, options.robust_scale);
  const int unknowns = options.estimate_yaw ? 3 : 2;
  const double prior_weight = options.prior_weight;
  Eigen::Matrix3d A = eq.JtJ;
  const double translation_prior = prior_weight * (eq.JtJ(0, 0) + eq.JtJ(1, 1)) + 1e-12;
  const Vec3x prior(translation_prior, translation_prior, prior_weight * eq.JtJ(2, 2) + 1e-12);
  const Vec3x start_offset(so_far.translation.x(), so_far.translation.y(), so_far.yaw);
  A.diagonal() += prior;
  const Vec3x b = eq.Jtr + prior.cwiseProduct(start_offset);
  Vec3x x = Vec3x::Zero();
  x.head(unknowns) = A.topLeftCorner(unknowns, unknowns).ldlt().solve(-b.head(unknowns));
  if (!x.allFinite()) return correction;
  correction.translation.x() = x[0];
  correction.translation.y() = x[1];
  correction.yaw = x[2];
  return correction;
}

void apply_correction(Points& points, const Vec3& body, const PlanarCorrection& correction) {
  const double c = std::cos(correction.yaw);
  const double s = std::sin(correction.yaw);
  for (Vec3& p : points) {
    const double qx = p.x() - body.x();
    const double qy = p.y() - body.y();
    p.x() = body.x() + c * qx - s * qy + correction.translation.x();
    p.y() = body.y() + s * qx + c * qy + correction.translation.y();
    p.z() += correction.translation.z();
  }
}

}  // namespace uavslam
