// Ringing: the frequency a force history rings at within a window, read by two
// independent estimators of the same prepared signal (signal_window.hpp):
//  - the peak of its Hann-windowed spectrum in the band (spectrum.hpp), what a plain
//    zero-padded FFT of the window shows;
//  - the most energetic damped sinusoid in the band of a matrix-pencil decomposition
//    (matrix_pencil.hpp), which also gives the ringing's damping ratio.
// The reading is their mean, and half their difference its uncertainty: a frequency the
// two do not agree on is not a clean ringing of one mode in that window.
#pragma once

#include <vector>

#include "post/matrix_pencil.hpp"
#include "post/spectrum.hpp"

namespace tirefe::post {

struct RingingBand {
  double min_frequency = 10.0;   // [Hz]
  double max_frequency = 200.0;  // [Hz]
};

struct RingingReading {
  double frequency = 0.0;     // mean of the two estimators [Hz]
  double uncertainty = 0.0;   // half their difference [Hz]
  SpectralPeak spectrum;      // Hann spectrum peak
  DampedComponent pencil;     // matrix-pencil component (frequency 0 if none in the band)
  double peak_to_peak = 0.0;  // of the raw samples in the window
  int samples = 0;            // raw samples in the window
};

/// Reads the window [from, to] of (times, values). Throws std::invalid_argument as
/// prepare_window() and spectrum_peak() do, and when no damped sinusoid of the
/// decomposition lies in the band.
RingingReading read_ringing(const std::vector<double>& times, const std::vector<double>& values, double from, double to,
                            const RingingBand& band = {});

}  // namespace tirefe::post
