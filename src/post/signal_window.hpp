// SignalWindow: one window of a sampled history, made ready for spectral estimators.
//
// Histories come from adaptive time steps, so the samples are unevenly spaced. Both
// ringing estimators (spectrum.hpp, matrix_pencil.hpp) read the same prepared signal:
//  - resampled by linear interpolation onto a uniform grid from the window's first sample,
//    with the median sample spacing of the window (the fine steps near an impact);
//  - its least-squares straight line removed (the quasi-static load change under the
//    ringing), so that neither estimator sees the trend as a low-frequency component.
#pragma once

#include <vector>

namespace tirefe::post {

struct SignalWindow {
  double start = 0.0;         // time of the first uniform sample [s]
  double step = 0.0;          // uniform sample spacing [s]
  std::vector<double> value;  // detrended samples
  double peak_to_peak = 0.0;  // of the raw samples in the window
  int raw_samples = 0;

  double nyquist() const { return 0.5 / step; }
};

/// The samples of (times, values) within [from, to], prepared as above. Throws
/// std::invalid_argument for mismatched lengths, a non-finite value, a window with
/// fewer than 8 samples, or times that do not increase.
SignalWindow prepare_window(const std::vector<double>& times, const std::vector<double>& values, double from,
                            double to);

}  // namespace tirefe::post
