#include "post/matrix_pencil.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace tirefe::post {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;

}  // namespace

std::vector<DampedComponent> matrix_pencil(const SignalWindow& window, const PencilSettings& settings) {
  const Eigen::Index n = static_cast<Eigen::Index>(window.value.size());
  if (n < 8) throw std::invalid_argument("matrix pencil: a window needs at least 8 samples");
  const Eigen::Index pencil = n / 2;
  Eigen::MatrixXd hankel(n - pencil, pencil + 1);
  for (Eigen::Index r = 0; r < hankel.rows(); ++r)
    for (Eigen::Index c = 0; c < hankel.cols(); ++c) hankel(r, c) = window.value[static_cast<size_t>(r + c)];
  // Y's right singular vectors are the eigenvectors of Y^T Y, whose eigenvalues are the
  // squared singular values: the symmetric eigenproblem takes two thirds of the SVD's time
  // or less. Squaring costs accuracy only in the small singular values; the kept ones exceed
  // a hundredth of the largest, and their subspace moves by round-off times (s_0 / s)^2 <= 1e4.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gram(hankel.transpose() * hankel);
  const Eigen::VectorXd squares = gram.eigenvalues().reverse();  // largest first
  if (!(squares[0] > 0.0)) return {};                            // a straight line: nothing rings
  const double kept_square = settings.relative_threshold * settings.relative_threshold * squares[0];
  Eigen::Index order = 0;
  while (order < squares.size() && order < settings.max_order && squares[order] > kept_square) ++order;
  const Eigen::MatrixXd kept = gram.eigenvectors().rightCols(order).rowwise().reverse();
  const Eigen::MatrixXd v1 = kept.topRows(pencil), v2 = kept.bottomRows(pencil);
  const Eigen::MatrixXd shift = v1.completeOrthogonalDecomposition().solve(v2);
  const Eigen::VectorXcd poles = Eigen::EigenSolver<Eigen::MatrixXd>(shift, false).eigenvalues();

  // Amplitudes: least squares of y_k = sum_i a_i z_i^k.
  Eigen::MatrixXcd vandermonde(n, order);
  for (Eigen::Index i = 0; i < order; ++i) {
    std::complex<double> power = 1.0;
    for (Eigen::Index k = 0; k < n; ++k, power *= poles[i]) vandermonde(k, i) = power;
  }
  Eigen::VectorXcd samples(n);
  for (Eigen::Index k = 0; k < n; ++k) samples[k] = window.value[static_cast<size_t>(k)];
  const Eigen::VectorXcd amplitudes = vandermonde.colPivHouseholderQr().solve(samples);

  std::vector<DampedComponent> components;
  for (Eigen::Index i = 0; i < order; ++i) {
    const double omega = std::arg(poles[i]) / window.step;
    if (!(omega > 0.0)) continue;  // the conjugate, or a non-oscillating exponential
    DampedComponent component;
    component.frequency = omega / kTwoPi;
    component.decay_rate = -std::log(std::abs(poles[i])) / window.step;
    component.damping_ratio = component.decay_rate / std::hypot(component.decay_rate, omega);
    component.amplitude = 2.0 * std::abs(amplitudes[i]);
    // Hann-weighted, as the spectrum weighs the window: the sinusoid's square averages half
    // its envelope's square over a period.
    const double ratio = std::norm(poles[i]);
    double envelope = 1.0, weighted = 0.0;
    for (Eigen::Index k = 0; k < n; ++k, envelope *= ratio) {
      const double s = std::sin(kPi * static_cast<double>(k) / static_cast<double>(n - 1));
      weighted += s * s * envelope;
    }
    component.energy = 0.5 * component.amplitude * component.amplitude * weighted;
    components.push_back(component);
  }
  std::sort(components.begin(), components.end(),
            [](const DampedComponent& a, const DampedComponent& b) { return a.energy > b.energy; });
  return components;
}

}  // namespace tirefe::post
