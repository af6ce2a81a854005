// Proportional load functions (FEAP's PROP): a scalar factor of time that scales
// nodal loads, prescribed displacements and pressures.
#pragma once

#include <functional>
#include <utility>
#include <vector>

namespace tirefe {

class LoadFunction {
 public:
  /// f(t) = t: the classic load-stepping ramp.
  static LoadFunction linear() {
    return LoadFunction([](double t) { return t; });
  }
  static LoadFunction constant(double value) {
    return LoadFunction([value](double) { return value; });
  }
  /// Piecewise-linear through (time, factor) points sorted by time; held constant
  /// outside the first and last point.
  static LoadFunction table(std::vector<std::pair<double, double>> points);

  explicit LoadFunction(std::function<double(double)> factor) : factor_(std::move(factor)) {}
  double operator()(double time) const { return factor_(time); }

 private:
  std::function<double(double)> factor_;
};

}  // namespace tirefe
