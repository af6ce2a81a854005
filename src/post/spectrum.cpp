#include "post/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "post/golden_section.hpp"

namespace tirefe::post {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Hann weights w_k = sin^2(pi k / (N - 1)).
std::vector<double> hann_weights(size_t count) {
  std::vector<double> weights(count);
  for (size_t k = 0; k < count; ++k) {
    const double s = std::sin(kPi * static_cast<double>(k) / static_cast<double>(count - 1));
    weights[k] = s * s;
  }
  return weights;
}

double amplitude_at(const SignalWindow& window, const std::vector<double>& weights, double weight_sum,
                    double frequency) {
  // exp(-i theta k) by a rotating phasor: one complex multiplication per sample.
  const double theta = 2.0 * kPi * frequency * window.step;
  const double c = std::cos(theta), s = std::sin(theta);
  double re = 0.0, im = 0.0, phasor_re = 1.0, phasor_im = 0.0;
  for (size_t k = 0; k < window.value.size(); ++k) {
    const double wy = weights[k] * window.value[k];
    re += wy * phasor_re;
    im -= wy * phasor_im;
    const double next_re = phasor_re * c - phasor_im * s;
    phasor_im = phasor_re * s + phasor_im * c;
    phasor_re = next_re;
  }
  return 2.0 * std::hypot(re, im) / weight_sum;
}

double sum(const std::vector<double>& values) {
  double total = 0.0;
  for (double value : values) total += value;
  return total;
}

}  // namespace

std::vector<double> hann_spectrum(const SignalWindow& window, const std::vector<double>& frequencies) {
  const std::vector<double> weights = hann_weights(window.value.size());
  const double weight_sum = sum(weights);
  std::vector<double> amplitudes;
  amplitudes.reserve(frequencies.size());
  for (double frequency : frequencies) amplitudes.push_back(amplitude_at(window, weights, weight_sum, frequency));
  return amplitudes;
}

SpectralPeak spectrum_peak(const SignalWindow& window, double min_frequency, double max_frequency) {
  if (!(min_frequency >= 0.0 && max_frequency > min_frequency))
    throw std::invalid_argument("spectrum: need 0 <= min_frequency < max_frequency");
  if (max_frequency > window.nyquist())
    throw std::invalid_argument("spectrum: the band reaches " + std::to_string(max_frequency) +
                                " Hz, past the Nyquist frequency " + std::to_string(window.nyquist()) +
                                " Hz of the window's samples");
  const std::vector<double> weights = hann_weights(window.value.size());
  const double weight_sum = sum(weights);
  const double grid = 1.0 / (16.0 * window.step * static_cast<double>(window.value.size()));
  const int points = static_cast<int>(std::ceil((max_frequency - min_frequency) / grid)) + 1;
  int best = 0;
  double best_amplitude = -1.0;
  for (int j = 0; j < points; ++j) {
    const double f = std::min(min_frequency + grid * j, max_frequency);
    const double amplitude = amplitude_at(window, weights, weight_sum, f);
    if (amplitude > best_amplitude) best = j, best_amplitude = amplitude;
  }
  const double low = std::max(min_frequency, min_frequency + grid * (best - 1));
  const double high = std::min(max_frequency, min_frequency + grid * (best + 1));
  const auto negative_amplitude = [&](double f) { return -amplitude_at(window, weights, weight_sum, f); };
  SpectralPeak peak;
  peak.frequency = golden_section_minimum(negative_amplitude, low, high);
  peak.amplitude = amplitude_at(window, weights, weight_sum, peak.frequency);
  if (peak.amplitude < best_amplitude) {  // the grid point itself (a band edge) was higher
    peak.frequency = std::min(min_frequency + grid * best, max_frequency);
    peak.amplitude = best_amplitude;
  }
  return peak;
}

}  // namespace tirefe::post
