// Spectrum: the Hann-windowed amplitude spectrum of a prepared window, and its peak.
//
//     X(f) = (2 / sum w) | sum_k w_k y_k exp(-i 2 pi f k h) |,   w_k = sin^2(pi k / (N - 1)),
//
// the single-sided amplitude of a sinusoid at f (a pure sine of amplitude A reads A at
// its frequency). This is the DFT of the window zero-padded without limit, evaluated at
// any frequency: an FFT of the same window zero-padded P times samples it at
// f = j / (P N h). The peak in a band is found on a grid 1 / (16 N h) fine and refined by
// golden sections, so it agrees with a zero-padded FFT's highest bin to its bin width.
#pragma once

#include <vector>

#include "post/signal_window.hpp"

namespace tirefe::post {

/// X(f) above at each of 'frequencies' [Hz].
std::vector<double> hann_spectrum(const SignalWindow& window, const std::vector<double>& frequencies);

struct SpectralPeak {
  double frequency = 0.0;  // [Hz]
  double amplitude = 0.0;  // X at the peak
};

/// The highest point of X(f) within [min_frequency, max_frequency]. Throws
/// std::invalid_argument when the band is empty or reaches past the Nyquist frequency.
SpectralPeak spectrum_peak(const SignalWindow& window, double min_frequency, double max_frequency);

}  // namespace tirefe::post
