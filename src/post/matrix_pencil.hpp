// Matrix pencil: a prepared window (signal_window.hpp) as a sum of damped exponentials,
//
//     y_k = sum_i a_i z_i^k,   z_i = exp((-sigma_i + i omega_i) h),
//
// after Hua and Sarkar (IEEE Trans. Acoust. Speech Signal Process. 38(5), 1990). The
// Hankel matrix Y (N - L rows, L + 1 columns, y_{r+c} at (r, c), pencil parameter L = N/2)
// has rank M for M exponentials. Its SVD Y = U S V^T keeps the M right singular vectors
// whose singular values exceed 'relative_threshold' times the largest (what is smaller is
// taken as the rest of a non-stationary signal rather than a component); they are found
// as the eigenvectors of Y^T Y. With V1 and V2 those vectors without their last and their
// first row, the poles z_i are the eigenvalues of pinv(V1) V2, and the amplitudes a_i the
// least-squares fit of the Vandermonde system.
// A real signal gives conjugate pairs: each pair is one damped sinusoid
// 2 |a| exp(-sigma t) cos(omega t + arg a), reported once, at omega > 0.
//
// Unlike an FFT peak, the pencil separates components closer than the window's
// resolution and gives each its decay; the two are independent readings of one signal.
#pragma once

#include <vector>

#include "post/signal_window.hpp"

namespace tirefe::post {

struct DampedComponent {
  double frequency = 0.0;      // omega / 2 pi [Hz]
  double decay_rate = 0.0;     // sigma [1/s]; negative: growing
  double damping_ratio = 0.0;  // sigma / sqrt(sigma^2 + omega^2)
  double amplitude = 0.0;      // 2 |a| at the window's start
  double energy = 0.0;         // sum over the window of its square, Hann-weighted as the spectrum
};

struct PencilSettings {
  double relative_threshold = 1e-2;  // singular values kept, relative to the largest
  int max_order = 24;                // exponentials at most (12 sinusoids)
};

/// The oscillating components (omega > 0) of the window, by decreasing energy (weighted by
/// the Hann window, so that "dominant" means what it means for the spectrum). Throws
/// std::invalid_argument for a window of fewer than 8 samples.
std::vector<DampedComponent> matrix_pencil(const SignalWindow& window, const PencilSettings& settings = {});

}  // namespace tirefe::post
