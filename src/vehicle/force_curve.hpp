// ForceCurve: a force as a piecewise-linear function of a deflection or a rate (a
// spring's force-deflection table, a damper's force-velocity table), extended linearly
// beyond its end points with the end segments' slopes.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace tirefe {

class ForceCurve {
 public:
  ForceCurve() = default;
  /// A straight line through the origin: force = slope * argument.
  static ForceCurve linear(double slope) { return ForceCurve({{0.0, 0.0}, {1.0, slope}}); }
  /// Points (argument, force) with increasing arguments, at least two.
  explicit ForceCurve(std::vector<std::pair<double, double>> points) : points_(std::move(points)) {
    if (points_.size() < 2) throw std::invalid_argument("a force curve needs at least two points");
    for (size_t i = 1; i < points_.size(); ++i)
      if (!(points_[i].first > points_[i - 1].first))
        throw std::invalid_argument("force curve arguments must increase (point " + std::to_string(i + 1) + ")");
  }

  bool empty() const { return points_.empty(); }
  double operator()(double argument) const {
    if (points_.empty()) return 0.0;
    const size_t i = segment(argument);
    return points_[i].second + slope(i) * (argument - points_[i].first);
  }
  /// d force / d argument (the slope of the segment holding the argument).
  double derivative(double argument) const { return points_.empty() ? 0.0 : slope(segment(argument)); }

 private:
  size_t segment(double argument) const {
    const auto above =
        std::upper_bound(points_.begin() + 1, points_.end() - 1, argument,
                         [](double value, const std::pair<double, double>& p) { return value < p.first; });
    return static_cast<size_t>(above - points_.begin()) - 1;
  }
  double slope(size_t i) const {
    return (points_[i + 1].second - points_[i].second) / (points_[i + 1].first - points_[i].first);
  }

  std::vector<std::pair<double, double>> points_;
};

}  // namespace tirefe
