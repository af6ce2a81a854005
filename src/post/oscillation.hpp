// Oscillation: the dominant damped oscillation in a short window of a force history.
//
// A spindle force after a cleat impact rings at the tire's modes for a few periods only
// (about four periods of the 88 Hz vertical mode while the tire rides on a 660 mm cleat at
// 51 km/h), too few for an FFT peak to resolve (its bins are 1/window wide). So the window
// is fitted in the least-squares sense by
//
//     y(t) = c0 + c1 (t - t0) + exp(-sigma (t - t0)) [a cos(omega (t - t0)) + b sin(omega (t - t0))],
//
// a trend (the quasi-static load change) plus one damped sinusoid. For fixed (omega, sigma)
// the model is linear in (c0, c1, a, b); omega and sigma are found by a grid search refined
// with golden sections (variable projection). Samples may be unevenly spaced (adaptive time
// steps).
#pragma once

#include <vector>

namespace tirefe::post {

struct Oscillation {
  double frequency = 0.0;     // [Hz]
  double amplitude = 0.0;     // of the sinusoid at the window's start
  double decay_rate = 0.0;    // sigma [1/s]
  double peak_to_peak = 0.0;  // of the raw samples in the window
  double rms_misfit = 0.0;    // of the fit, in the units of the samples
  int samples = 0;
};

struct OscillationSearch {
  double min_frequency = 5.0;     // [Hz]
  double max_frequency = 400.0;   // [Hz]
  double max_decay_rate = 200.0;  // [1/s]
};

/// The dominant oscillation of 'values' sampled at 'times' within [from, to]. Throws
/// std::invalid_argument when the window holds fewer than 8 samples or too few per period
/// of the highest frequency searched.
Oscillation dominant_oscillation(const std::vector<double>& times, const std::vector<double>& values, double from,
                                 double to, const OscillationSearch& search = {});

}  // namespace tirefe::post
