#include "core/load_function.hpp"

#include <algorithm>

#include "core/mesh.hpp"

namespace tirefe {

LoadFunction LoadFunction::table(std::vector<std::pair<double, double>> points) {
  if (points.empty()) throw ModelError("a load function table needs at least one (time, factor) point");
  for (size_t i = 1; i < points.size(); ++i)
    if (!(points[i].first > points[i - 1].first))
      throw ModelError("load function table times must increase strictly (point " + std::to_string(i + 1) + ")");
  return LoadFunction([points = std::move(points)](double t) {
    if (t <= points.front().first) return points.front().second;
    if (t >= points.back().first) return points.back().second;
    auto upper = std::upper_bound(points.begin(), points.end(), t,
                                  [](double time, const auto& point) { return time < point.first; });
    auto lower = upper - 1;
    double weight = (t - lower->first) / (upper->first - lower->first);
    return lower->second + weight * (upper->second - lower->second);
  });
}

}  // namespace tirefe
