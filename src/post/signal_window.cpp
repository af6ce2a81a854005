#include "post/signal_window.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tirefe::post {

SignalWindow prepare_window(const std::vector<double>& times, const std::vector<double>& values, double from,
                            double to) {
  if (times.size() != values.size()) throw std::invalid_argument("times and values differ in length");
  if (!(to > from)) throw std::invalid_argument("the window's end must come after its start");
  std::vector<double> t, y;
  for (size_t i = 0; i < times.size(); ++i) {
    if (!(times[i] >= from && times[i] <= to)) continue;
    if (!std::isfinite(values[i])) throw std::invalid_argument("a value in the window is not finite");
    if (!t.empty() && !(times[i] > t.back())) throw std::invalid_argument("sample times must increase");
    t.push_back(times[i]);
    y.push_back(values[i]);
  }
  const size_t n = t.size();
  if (n < 8)
    throw std::invalid_argument("the window [" + std::to_string(from) + ", " + std::to_string(to) + "] s holds " +
                                std::to_string(n) + " samples; at least 8 are needed");
  std::vector<double> spacing(n - 1);
  for (size_t i = 0; i + 1 < n; ++i) spacing[i] = t[i + 1] - t[i];
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());

  SignalWindow window;
  window.start = t.front();
  window.step = spacing[spacing.size() / 2];
  window.raw_samples = static_cast<int>(n);
  const auto [low, high] = std::minmax_element(y.begin(), y.end());
  window.peak_to_peak = *high - *low;
  const size_t count = static_cast<size_t>(std::floor((t.back() - t.front()) / window.step * (1.0 + 1e-12))) + 1;
  window.value.resize(count);
  size_t segment = 0;
  for (size_t k = 0; k < count; ++k) {
    const double time = window.start + window.step * static_cast<double>(k);
    while (segment + 2 < n && t[segment + 1] < time) ++segment;
    const double weight = std::clamp((time - t[segment]) / (t[segment + 1] - t[segment]), 0.0, 1.0);
    window.value[k] = y[segment] + weight * (y[segment + 1] - y[segment]);
  }
  // Remove the least-squares line a + b (k - mean k).
  const double mean_index = 0.5 * static_cast<double>(count - 1);
  double sum = 0.0, moment = 0.0, spread = 0.0;
  for (size_t k = 0; k < count; ++k) {
    const double x = static_cast<double>(k) - mean_index;
    sum += window.value[k];
    moment += x * window.value[k];
    spread += x * x;
  }
  const double mean = sum / static_cast<double>(count), slope = spread > 0.0 ? moment / spread : 0.0;
  for (size_t k = 0; k < count; ++k) window.value[k] -= mean + slope * (static_cast<double>(k) - mean_index);
  return window;
}

}  // namespace tirefe::post
