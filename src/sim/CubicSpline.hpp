// A clamped cubic spline through (t_i, y_i): C2, with given first derivatives at both ends.
#pragma once

#include <cstddef>
#include <vector>

namespace uavslam::sim {

class CubicSpline {
 public:
  // knots strictly increasing, same size as values, at least 2.
  CubicSpline(std::vector<double> knots, std::vector<double> values, double start_slope,
              double end_slope);

  // t outside the knots is clamped to them.
  double value(double t) const;
  double first_derivative(double t) const;
  double second_derivative(double t) const;

 private:
  // The segment [t_i, t_i+1] holding t, and t's normalised position in it.
  struct Locus {
    std::size_t i;
    double h;  // segment length
    double a;  // weight of knot i: (t_i+1 - t) / h
    double b;  // weight of knot i+1: (t - t_i) / h
  };
  Locus locate(double t) const;

  std::vector<double> knots_;
  std::vector<double> values_;
  std::vector<double> second_derivatives_;  // at the knots
};

}  // namespace uavslam::sim
