#include "post/oscillation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "post/golden_section.hpp"

namespace tirefe::post {

namespace {

constexpr double kTwoPi = 6.283185307179586;

/// The samples of one window, time measured from its start.
struct Window {
  Eigen::VectorXd time, value;
};

/// Residual norm of the linear least-squares fit for one (omega, sigma); fills the
/// coefficients (c0, c1, a, b).
double misfit(const Window& window, double omega, double sigma, Eigen::Vector4d* coefficients = nullptr) {
  const Eigen::Index n = window.time.size();
  Eigen::MatrixXd basis(n, 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = window.time[i];
    const double envelope = std::exp(-sigma * t);
    basis(i, 0) = 1.0;
    basis(i, 1) = t;
    basis(i, 2) = envelope * std::cos(omega * t);
    basis(i, 3) = envelope * std::sin(omega * t);
  }
  const Eigen::Vector4d c = basis.colPivHouseholderQr().solve(window.value);
  if (coefficients) *coefficients = c;
  return (basis * c - window.value).norm();
}

}  // namespace

Oscillation dominant_oscillation(const std::vector<double>& times, const std::vector<double>& values, double from,
                                 double to, const OscillationSearch& search) {
  if (times.size() != values.size()) throw std::invalid_argument("oscillation: times and values differ in length");
  if (!(to > from)) throw std::invalid_argument("oscillation: the window's end must come after its start");
  if (!(search.max_frequency > search.min_frequency && search.min_frequency > 0.0))
    throw std::invalid_argument("oscillation: need 0 < min_frequency < max_frequency");
  std::vector<double> t, y;
  for (size_t i = 0; i < times.size(); ++i)
    if (times[i] >= from && times[i] <= to) {
      if (!std::isfinite(values[i])) throw std::invalid_argument("oscillation: a value in the window is not finite");
      t.push_back(times[i] - from);
      y.push_back(values[i]);
    }
  const int n = static_cast<int>(t.size());
  if (n < 8)
    throw std::invalid_argument("oscillation: the window [" + std::to_string(from) + ", " + std::to_string(to) +
                                "] s holds " + std::to_string(n) + " samples; at least 8 are needed");
  const double span = t.back() - t.front();
  if (!(span > 0.0)) throw std::invalid_argument("oscillation: the window's samples span no time");
  // Nyquist in the mean: at least two samples per period of the highest frequency.
  if (search.max_frequency * 2.0 * span / (n - 1) > 1.0)
    throw std::invalid_argument("oscillation: " + std::to_string(n) + " samples over " + std::to_string(span) +
                                " s are too few for frequencies up to " + std::to_string(search.max_frequency) +
                                " Hz; lower max_frequency or sample more finely");
  Window window{Eigen::Map<Eigen::VectorXd>(t.data(), n), Eigen::Map<Eigen::VectorXd>(y.data(), n)};

  // Grid: a quarter of the Fourier resolution 1/span in frequency, a few decay rates.
  const double frequency_step = 0.25 / span;
  const int decay_steps = 8;
  double best = std::numeric_limits<double>::infinity(), best_omega = 0.0, best_sigma = 0.0;
  for (double f = search.min_frequency; f <= search.max_frequency; f += frequency_step)
    for (int k = 0; k <= decay_steps; ++k) {
      const double sigma = search.max_decay_rate * k / decay_steps;
      const double r = misfit(window, kTwoPi * f, sigma);
      if (r < best) best = r, best_omega = kTwoPi * f, best_sigma = sigma;
    }
  // Refine omega and sigma alternately within one grid cell.
  const double omega_cell = kTwoPi * frequency_step, sigma_cell = search.max_decay_rate / decay_steps;
  for (int sweep = 0; sweep < 3; ++sweep) {
    best_omega = golden_section_minimum([&](double omega) { return misfit(window, omega, best_sigma); },
                                        std::max(best_omega - omega_cell, 1e-9), best_omega + omega_cell);
    best_sigma = golden_section_minimum([&](double sigma) { return misfit(window, best_omega, sigma); },
                                        std::max(best_sigma - sigma_cell, 0.0), best_sigma + sigma_cell);
  }
  Eigen::Vector4d c;
  const double residual = misfit(window, best_omega, best_sigma, &c);
  Oscillation result;
  result.frequency = best_omega / kTwoPi;
  result.amplitude = std::hypot(c[2], c[3]);
  result.decay_rate = best_sigma;
  result.peak_to_peak = window.value.maxCoeff() - window.value.minCoeff();
  result.rms_misfit = residual / std::sqrt(static_cast<double>(n));
  result.samples = n;
  return result;
}

}  // namespace tirefe::post
