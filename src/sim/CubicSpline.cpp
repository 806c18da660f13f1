#include "sim/CubicSpline.hpp"

#include <algorithm>
#include <utility>

namespace uavslam::sim {

namespace {

// Second derivatives M_i of the clamped spline: a tridiagonal system solved with the Thomas
// algorithm (the system is diagonally dominant, so no pivoting is needed).
std::vector<double> solve_second_derivatives(const std::vector<double>& t,
                                             const std::vector<double>& y, double start_slope,
                                             double end_slope) {
  const std::size_t n = t.size();
  std::vector<double> lower(n, 0.0), diagonal(n, 0.0), upper(n, 0.0), rhs(n, 0.0);
  const double h_first = t[1] - t[0];
  diagonal[0] = 2.0 * h_first;
  upper[0] = h_first;
  rhs[0] = 6.0 * ((y[1] - y[0]) / h_first - start_slope);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h_before = t[i] - t[i - 1];
    const double h_after = t[i + 1] - t[i];
    lower[i] = h_before;
    diagonal[i] = 2.0 * (h_before + h_after);
    upper[i] = h_after;
    rhs[i] = 6.0 * ((y[i + 1] - y[i]) / h_after - (y[i] - y[i - 1]) / h_before);
  }
  const double h_last = t[n - 1] - t[n - 2];
  lower[n - 1] = h_last;
  diagonal[n - 1] = 2.0 * h_last;
  rhs[n - 1] = 6.0 * (end_slope - (y[n - 1] - y[n - 2]) / h_last);

  for (std::size_t i = 1; i < n; ++i) {  // forward elimination
    const double factor = lower[i] / diagonal[i - 1];
    diagonal[i] -= factor * upper[i - 1];
    rhs[i] -= factor * rhs[i - 1];
  }
  std::vector<double> m(n);
  m[n - 1] = rhs[n - 1] / diagonal[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) m[i] = (rhs[i] - upper[i] * m[i + 1]) / diagonal[i];
  return m;
}

}  // namespace

CubicSpline::CubicSpline(std::vector<double> knots, std::vector<double> values, double start_slope,
                         double end_slope)
    : knots_(std::move(knots)),
      values_(std::move(values)),
      second_derivatives_(solve_second_derivatives(knots_, values_, start_slope, end_slope)) {}

CubicSpline::Locus CubicSpline::locate(double t) const {
  t = std::clamp(t, knots_.front(), knots_.back());
  const auto after = std::upper_bound(knots_.begin() + 1, knots_.end() - 1, t);
  const std::size_t i = static_cast<std::size_t>(after - knots_.begin()) - 1;
  const double h = knots_[i + 1] - knots_[i];
  const double b = (t - knots_[i]) / h;
  return {i, h, 1.0 - b, b};
}

double CubicSpline::value(double t) const {
  const Locus l = locate(t);
  const double m0 = second_derivatives_[l.i], m1 = second_derivatives_[l.i + 1];
  return l.a * values_[l.i] + l.b * values_[l.i + 1] +
         ((l.a * l.a * l.a - l.a) * m0 + (l.b * l.b * l.b - l.b) * m1) * l.h * l.h / 6.0;
}

double CubicSpline::first_derivative(double t) const {
  const Locus l = locate(t);
  const double m0 = second_derivatives_[l.i], m1 = second_derivatives_[l.i + 1];
  return (values_[l.i + 1] - values_[l.i]) / l.h - (3.0 * l.a * l.a - 1.0) / 6.0 * l.h * m0 +
         (3.0 * l.b * l.b - 1.0) / 6.0 * l.h * m1;
}

double CubicSpline::second_derivative(double t) const {
  const Locus l = locate(t);
  return l.a * second_derivatives_[l.i] + l.b * second_derivatives_[l.i + 1];
}

}  // namespace uavslam::sim
