// SidewallWedge and its section law. The math is in sidewall.hpp; this file adds the
// linearisation. With dP = B du, B = [I, rho_perp, -N_a I, 0, -N_b I, 0] (rho_perp =
// k x rho), de_y = e_x (e_x.dP)/L, de_x = -e_y (e_x.dP)/L, dL = e_y.dP and
// dgamma = e_x.dP/L - dtheta_S, the elastic traction T = F e_y + S e_x (S = k_gamma gamma)
// varies as
//   dT = [F' e_y e_y^T + ((F + k_gamma) e_x - S e_y) e_x^T / L] dP - k_gamma e_x dtheta_S,
// the damping traction D = -C_d v (C_d = c_r e_y e_y^T + c_t e_x e_x^T) as
//   dD/du = -(c_r - c_t)(v_x e_y + v_y e_x) e_x^T dP / L - omega_S C_d k x (dP - rho_perp dtheta_S),
//   dD/dv = C_d (B - L e_x e_theta^T),
// and the residual sum_q (l/2) B^T T adds the geometric terms of B (d rho_perp/dtheta_S
// = -rho) and of the deformed chord length l (dl = t.(du_b - du_a)).
#include "elements/sidewall.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/batch_of_one.hpp"
#include "core/simd_clones.hpp"
#include "elements/sine_cosine.hpp"

namespace tirefe {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Two-point Gauss rule on xi in [0, 1]: exact for the cubic N_i T of a smoothly varying
// traction, and the integrand varies little over one of 50-100 wedges.
constexpr double kGaussOffset = 0.28867513459481288225;  // 1 / (2 sqrt 3)
constexpr double kGaussPoints[SidewallWedge::kQuadraturePoints] = {0.5 - kGaussOffset, 0.5 + kGaussOffset};
constexpr double kGaussWeight = 0.5;

/// The cord at one point of one wedge (sidewall.hpp), from the spin's cosine and sine, the
/// point's reference rim offset r_rim e_r and tread point, the spindle's reference position,
/// the shape functions N_a, N_b and the wedge's displacements u[k * stride]: written once
/// for the batch's loop over wedges and for cord_state().
struct CordPoint {
  double rim_x, rim_y;    // rho = R(theta_S) r_rim e_r
  double cord_x, cord_y;  // P = x_r - x_t
  double e_y_x, e_y_y;    // e_y = P / L
  double chord;           // L
  double cross, dot;      // of the turned reference cord -rho with e_y: gamma's (shear_angle)
};
inline CordPoint cord_point(double cos_spin, double sin_spin, double offset_x, double offset_y, double reference_x,
                            double reference_y, double spindle_x, double spindle_y, double shape_a, double shape_b,
                            const double* u, int stride) {
  CordPoint p;
  p.rim_x = cos_spin * offset_x - sin_spin * offset_y;
  p.rim_y = sin_spin * offset_x + cos_spin * offset_y;
  const double tread_x = reference_x + shape_a * u[3 * stride] + shape_b * u[6 * stride];
  const double tread_y = reference_y + shape_a * u[4 * stride] + shape_b * u[7 * stride];
  p.cord_x = spindle_x + u[0] + p.rim_x - tread_x;
  p.cord_y = spindle_y + u[stride] + p.rim_y - tread_y;
  p.chord = std::sqrt(p.cord_x * p.cord_x + p.cord_y * p.cord_y);
  p.e_y_x = p.cord_x / p.chord;
  p.e_y_y = p.cord_y / p.chord;
  p.cross = -p.rim_x * p.e_y_y - -p.rim_y * p.e_y_x;
  p.dot = -p.rim_x * p.e_y_x + -p.rim_y * p.e_y_y;
  return p;
}

/// gamma: from the rotated reference cord -rho (length r_rim) to e_y. Within 45 degrees
/// its sine is well conditioned (d gamma = d sin / cos gamma) and asin costs a fraction of
/// atan2, which takes over beyond.
inline double shear_angle(double cross, double dot, double rim_radius) {
  return std::abs(cross) <= dot ? std::asin(cross / rim_radius) : std::atan2(cross, dot);
}

/// Root of f(alpha) = sin(alpha) - ratio alpha on (0, pi] for 0 <= ratio < 1. f is
/// positive below the root and negative above (sinc decreases), which keeps a bracket
/// for the bisection safeguard. The start is the series inversion of sinc about 0 to
/// eighth order, alpha^2 = sum_k c_k y^k with y = 1 - ratio: 1e-9 accurate at the
/// service ratio 0.85, 3e-7 at 0.7, 2e-5 at 0.5. Halley's steps (f'' = -sin alpha comes
/// free with f) converge cubically: the error after a step d is about K d^3 with
/// K <= 2 / alpha^2, so a step |d| <= 1e-5 alpha leaves 2e-15 alpha, and every chord of a
/// working tire needs a single sine and cosine (sine_cosine.hpp, inline). Sine and cosine
/// follow by Taylor to second order (error d^3/6, below round-off). Its parts are
/// written once for solve_half_angle (one chord) and solve_half_angles (many, vectorised).
/// The series start; for ratios in [0, 1) it stays below 3.12 (its sum at ratio 0) < pi.
inline double half_angle_series(double ratio) {
  const double y = 1.0 - ratio;
  // clang-format off
  constexpr double c[8] = {6.0, 9.0 / 5.0, 144.0 / 175.0, 78.0 / 175.0, 89226.0 / 336875.0,
                           522063.0 / 3128125.0, 83924688.0 / 766390625.0, 438337548.0 / 5922109375.0};
  // clang-format on
  double series = c[7];
#pragma GCC unroll 7
  for (int k = 6; k >= 0; --k) series = c[k] + y * series;
  return std::sqrt(y * series);
}

// One safeguarded Halley step from alpha, its bracket moved to alpha.
struct HalleyStep {
  double next, step;
};
inline HalleyStep halley_step(double ratio, double alpha, const SineCosine& turn, double& low, double& high) {
  const double residual = turn.sin - ratio * alpha;
  low = residual > 0.0 ? alpha : low;
  high = residual > 0.0 ? high : alpha;
  const double slope = turn.cos - ratio;
  double next = alpha - 2.0 * residual * slope / (2.0 * slope * slope + residual * turn.sin);
  // A converged step may land on the bracket end just moved to alpha: keep it.
  if (!(next >= low && next <= high)) next = 0.5 * (low + high);
  return {next, next - alpha};
}

// Whether a step ends the solve, and the solution it gives: cosine and sine by Taylor.
inline bool halley_converged(double alpha, double step) { return std::abs(step) <= 1e-5 * alpha; }
inline ArchSolution halley_solution(double next, double step, const SineCosine& turn) {
  const double half_square = 0.5 * step * step;
  return {next, turn.cos - step * turn.sin - half_square * turn.cos,
          turn.sin + step * turn.cos - half_square * turn.sin};
}

ArchSolution solve_half_angle(double ratio) {
  double alpha = std::min(half_angle_series(ratio), kPi);
  double low = 0.0, high = kPi;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const SineCosine turn = sine_cosine(alpha);  // inline: no call into the math library
    if (turn.sin - ratio * alpha == 0.0) break;
    const HalleyStep step = halley_step(ratio, alpha, turn, low, high);
    if (halley_converged(alpha, step.step)) return halley_solution(step.next, step.step, turn);
    alpha = step.next;
    if (high - low <= 1e-15 * high) break;  // the end of a bisection run
  }
  const SineCosine turn = sine_cosine(alpha);
  return {alpha, turn.cos, turn.sin};
}

// F and dF/dalpha on the arch branch, at a half-angle with known cos and sin: the membrane
// n_sw p r sin(theta) with r = l_sw/(2 alpha), sin(theta) = cos(alpha), and the bending.
struct ArchForce {
  double force, dforce_dhalf_angle;
};
inline ArchForce arch_force(double membrane_scale, double signed_bending, double alpha, double cos_half,
                            double sin_half, double alpha0) {
  const double bending_shape = alpha * (alpha - alpha0);
  return {membrane_scale * cos_half / alpha + signed_bending * bending_shape * cos_half,
          -membrane_scale * (alpha * sin_half + cos_half) / (alpha * alpha) +
              signed_bending * ((2.0 * alpha - alpha0) * cos_half - bending_shape * sin_half)};
}

// F and dF/dL of a chord L on the arch branch: dalpha/dL = alpha / (l_sw cos(alpha) - L).
inline SidewallLaw::CordForce arch_law(double membrane_scale, double signed_bending, double cord_length, double chord,
                                       double alpha, double cos_half, double sin_half, double alpha0) {
  const ArchForce arch = arch_force(membrane_scale, signed_bending, alpha, cos_half, sin_half, alpha0);
  return {arch.force, arch.dforce_dhalf_angle * alpha / (cord_length * cos_half - chord)};
}

void require(bool condition, const std::string& message) {
  if (!condition) throw ModelError("sidewall: " + message);
}

}  // namespace

TIREFE_SIMD_CLONES void solve_half_angles(const double* ratio, int count, double* half_angle, double* cos_half,
                                          double* sin_half) {
  // solve_half_angle's first iteration, vectorised: it ends the solve of every chord of a
  // working tire. A chord it does not end is marked, then solved alone from the start.
  // The arithmetic is halley_step's and halley_solution's, written out: the vectoriser
  // takes selects, not the bracket moved through a reference.
  constexpr double kUnsolved = std::numeric_limits<double>::quiet_NaN();
#pragma omp simd
  for (int i = 0; i < count; ++i) {
    const double r = ratio[i], alpha = half_angle_series(r);  // below pi: solve_half_angle's start
    const SineCosine turn = sine_cosine(alpha);
    const double residual = turn.sin - r * alpha;
    const double low = residual > 0.0 ? alpha : 0.0, high = residual > 0.0 ? kPi : alpha;
    const double slope = turn.cos - r;
    double next = alpha - 2.0 * residual * slope / (2.0 * slope * slope + residual * turn.sin);
    if (!(next >= low && next <= high)) next = 0.5 * (low + high);
    const double step = next - alpha, half_square = 0.5 * step * step;
    const bool root = residual == 0.0;
    half_angle[i] = root ? alpha : halley_converged(alpha, step) ? next : kUnsolved;
    cos_half[i] = root ? turn.cos : turn.cos - step * turn.sin - half_square * turn.cos;
    sin_half[i] = root ? turn.sin : turn.sin + step * turn.cos - half_square * turn.sin;
  }
  for (int i = 0; i < count; ++i) {
    if (!std::isnan(half_angle[i])) continue;
    const ArchSolution arch = solve_half_angle(ratio[i]);
    half_angle[i] = arch.half_angle;
    cos_half[i] = arch.cos_half;
    sin_half[i] = arch.sin_half;
  }
}

double ArchShape::meridian_angle() const { return 0.5 * kPi - half_angle; }
double ArchShape::radius(double cord_length) const { return cord_length / (2.0 * half_angle); }

ArchShape solve_arch(double chord, double cord_length) {
  const double ratio = chord / cord_length;
  if (!(cord_length > 0.0) || !(ratio >= 0.0 && ratio < 1.0))
    throw std::domain_error("sidewall arch: no circular arch of length " + std::to_string(cord_length) +
                            " m over a chord of " + std::to_string(chord) + " m");
  const ArchSolution arch = solve_half_angle(ratio);
  // Eq. 1 as g(alpha, L) = l_sw sin(alpha) - L alpha = 0: dalpha/dL = alpha / (l_sw cos(alpha) - L) < 0.
  return {arch.half_angle, arch.half_angle / (cord_length * arch.cos_half - chord)};
}

void SidewallProperties::check() const {
  auto finite = [](double value) { return std::isfinite(value); };
  require(finite(rim_radius) && rim_radius > 0.0, "the rim radius must be positive");
  require(finite(cord_length) && cord_length > 0.0, "the cord length l_sw must be positive");
  require(sidewall_count >= 1, "the sidewall count n_sw must be at least 1");
  require(finite(bending_stiffness) && bending_stiffness >= 0.0, "the bending stiffness k_sw must be >= 0");
  require(bending_sign == 1.0 || bending_sign == -1.0, "the bending sign must be +1 or -1");
  require(finite(shear_stiffness) && shear_stiffness >= 0.0, "the shear stiffness k_gamma must be >= 0");
  require(finite(radial_damping) && radial_damping >= 0.0, "the radial damping c_r must be >= 0");
  require(finite(circumferential_damping) && circumferential_damping >= 0.0,
          "the circumferential damping c_t must be >= 0");
  require(straight_cord_half_angle > 0.0 && straight_cord_half_angle <= 0.5,
          "the straight-cord half-angle alpha* must lie in (0, 0.5] rad");
}

SidewallLaw::SidewallLaw(const SidewallProperties& properties) : properties_(properties) {
  properties_.check();
  const double l = properties_.cord_length;
  signed_bending_ = properties_.bending_sign * properties_.bending_stiffness * 4.0 / (l * l);
  const double switch_half_angle = properties_.straight_cord_half_angle;
  switch_cos_ = std::cos(switch_half_angle);
  switch_sin_ = std::sin(switch_half_angle);
  switch_chord_ = l * switch_sin_ / switch_half_angle;
  switch_dhalf_angle_dchord_ = switch_half_angle / (l * switch_cos_ - switch_chord_);
}

double SidewallLaw::reference_half_angle(double chord) const {
  require(chord > 0.0 && chord < switch_chord_,
          "the reference cord spans " + std::to_string(chord) + " m, but it must be shorter than " +
              std::to_string(switch_chord_) + " m (the sidewall length l_sw = " +
              std::to_string(properties_.cord_length) + " m less the near-straight range)");
  return solve_arch(chord, properties_.cord_length).half_angle;
}

SidewallLaw::CordForce SidewallLaw::arch_cord_force(double chord, const ArchSolution& arch, double alpha0,
                                                    double pressure) const {
  return arch_law(membrane_scale(pressure), signed_bending_, properties_.cord_length, chord, arch.half_angle,
                  arch.cos_half, arch.sin_half, alpha0);
}

SidewallLaw::CordForce SidewallLaw::cord_force(double chord, double alpha0, double pressure) const {
  if (chord < switch_chord_)
    return arch_cord_force(chord, solve_half_angle(chord / properties_.cord_length), alpha0, pressure);
  // Near-straight or stretched cord: the linear continuation of the arch law from L*.
  const ArchForce start = arch_force(membrane_scale(pressure), signed_bending_, properties_.straight_cord_half_angle,
                                     switch_cos_, switch_sin_, alpha0);
  const double stiffness = start.dforce_dhalf_angle * switch_dhalf_angle_dchord_;
  return {start.force + stiffness * (chord - switch_chord_), stiffness};
}

SidewallWedge::SidewallWedge(const Eigen::Vector2d& spindle, const Eigen::Vector2d& tread_a,
                             const Eigen::Vector2d& tread_b, const SidewallProperties& properties,
                             std::shared_ptr<const PressureSchedule> pressure)
    : law_(properties), pressure_(std::move(pressure)), spindle_(spindle), tread_a_(tread_a), tread_b_(tread_b) {
  require(pressure_ != nullptr, "a pressure schedule is required (it may be zero)");
  require((tread_b - tread_a).norm() > 0.0, "the two tread nodes coincide");
  for (int q = 0; q < kQuadraturePoints; ++q) {
    const double xi = kGaussPoints[q];
    reference_tread_[q] = (1.0 - xi) * tread_a + xi * tread_b;
    const Eigen::Vector2d radial = reference_tread_[q] - spindle;
    const double distance = radial.norm();
    require(distance > properties.rim_radius,
            "a tread point lies inside the rim (distance " + std::to_string(distance) + " m from the spindle)");
    reference_rim_offset_[q] = (properties.rim_radius / distance) * radial;
    reference_half_angle_[q] = law_.reference_half_angle(distance - properties.rim_radius);
  }
}

SidewallWedge::CordState SidewallWedge::cord_state(const Vector& displacement, int q) const {
  const double shape_b = kGaussPoints[q];
  const CordPoint p = cord_point(std::cos(displacement[2]), std::sin(displacement[2]), reference_rim_offset_[q].x(),
                                 reference_rim_offset_[q].y(), reference_tread_[q].x(), reference_tread_[q].y(),
                                 spindle_.x(), spindle_.y(), 1.0 - shape_b, shape_b, displacement.data(), 1);
  return {p.chord, shear_angle(p.cross, p.dot, law_.properties().rim_radius)};
}

void SidewallWedge::evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&, History&,
                             Vector& residual, Matrix* tangent) const {
  evaluate_as_batch(*this, local, context, residual, tangent);
}

// The batch path: the wedge's physics, written once per wedge on arrays indexed by the
// wedge, so that the loops over wedges vectorise; evaluate() is its block of one.
namespace {
constexpr int kActiveDofs[] = {0, 1, 2, 3, 4, 6, 7};  // all but the tread rotations
}

SidewallWedge::Batch::Batch(const std::vector<SidewallWedge>& wedges) { assign(wedges); }

void SidewallWedge::Batch::assign(const std::vector<SidewallWedge>& wedges) {
  wedges_ = wedges;
  damped_ = false;
  const size_t n = wedges_.size();
  for (auto* field : {&tread_a_x_, &tread_a_y_, &tread_b_x_, &tread_b_y_, &shear_stiffness_, &radial_damping_,
                      &circumferential_damping_})
    field->resize(n);
  for (auto* field : {&rim_x_, &rim_y_, &cord_x_, &cord_y_, &e_y_x_, &e_y_y_, &chord_, &force_, &stiffness_,
                      &shear_angle_, &ratio_, &half_angle_, &cos_half_, &sin_half_})
    field->resize(kQuadraturePoints * n);
  for (auto* field : {&reference_tread_x_, &reference_tread_y_, &reference_rim_x_, &reference_rim_y_,
                      &reference_half_angle_, &cross_, &dot_})
    field->resize(kQuadraturePoints * n);
  for (auto* field : {&spindle_x_, &spindle_y_, &cord_length_, &switch_chord_, &rim_radius_, &signed_bending_,
                      &cos_spin_, &sin_spin_, &membrane_scale_})
    field->resize(n);
  // The entries the passes never write (idle DOFs') stay zero: cleared for a new layout alone,
  // so that a batch given other elements of the same number allocates and clears nothing.
  if (residual_.size() != kDofs * n) {
    residual_.assign(kDofs * n, 0.0);
    tangent_.assign(kDofs * kDofs * n, 0.0);
  }
  for (size_t e = 0; e < n; ++e) {
    const SidewallWedge& wedge = wedges_[e];
    for (int q = 0; q < kQuadraturePoints; ++q) {
      const size_t i = q * n + e;
      reference_tread_x_[i] = wedge.reference_tread_[q].x();
      reference_tread_y_[i] = wedge.reference_tread_[q].y();
      reference_rim_x_[i] = wedge.reference_rim_offset_[q].x();
      reference_rim_y_[i] = wedge.reference_rim_offset_[q].y();
      reference_half_angle_[i] = wedge.reference_half_angle_[q];
    }
    spindle_x_[e] = wedge.spindle_.x();
    spindle_y_[e] = wedge.spindle_.y();
    cord_length_[e] = wedge.law_.properties().cord_length;
    switch_chord_[e] = wedge.law_.switch_chord();
    rim_radius_[e] = wedge.law_.properties().rim_radius;
    signed_bending_[e] = wedge.law_.signed_bending();
    tread_a_x_[e] = wedge.tread_a_.x();
    tread_a_y_[e] = wedge.tread_a_.y();
    tread_b_x_[e] = wedge.tread_b_.x();
    tread_b_y_[e] = wedge.tread_b_.y();
    const SidewallProperties& properties = wedge.law_.properties();
    shear_stiffness_[e] = properties.shear_stiffness;
    radial_damping_[e] = properties.radial_damping;
    circumferential_damping_[e] = properties.circumferential_damping;
    damped_ = damped_ || properties.radial_damping != 0.0 || properties.circumferential_damping != 0.0;
  }
}

void SidewallWedge::Batch::solve_cords(const BlockValues& values, double time) {
  const int n = size();
  const double* u = values.displacement;
  // Every wedge of a tire turns with one spindle and reads one pressure: the spin's sine
  // and cosine and the pressure are computed once.
  double spin = std::numeric_limits<double>::quiet_NaN(), cos_spin = 0.0, sin_spin = 0.0;
  const PressureSchedule* schedule = nullptr;
  double pressure = 0.0;
  for (int e = 0; e < n; ++e) {
    const SidewallWedge& wedge = wedges_[e];
    if (!(u[2 * n + e] == spin)) {
      spin = u[2 * n + e];
      cos_spin = std::cos(spin);
      sin_spin = std::sin(spin);
    }
    if (wedge.pressure_.get() != schedule) {
      schedule = wedge.pressure_.get();
      pressure = schedule->at(time);
    }
    cos_spin_[e] = cos_spin;
    sin_spin_[e] = sin_spin;
    membrane_scale_[e] = wedge.law_.membrane_scale(pressure);
  }
  for (int q = 0; q < kQuadraturePoints; ++q) add_cords(u, q);
  for (int i = 0; i < kQuadraturePoints * n; ++i) {
    shear_angle_[i] = shear_angle(cross_[i], dot_[i], rim_radius_[i % n]);
  }
  solve_half_angles(ratio_.data(), kQuadraturePoints * n, half_angle_.data(), cos_half_.data(), sin_half_.data());
  for (int q = 0; q < kQuadraturePoints; ++q) add_cord_forces(q);
  for (int e = 0; e < n; ++e) {
    const SidewallWedge& wedge = wedges_[e];
    for (int q = 0; q < kQuadraturePoints; ++q) {
      const int i = q * n + e;
      if (chord_[i] < switch_chord_[e]) continue;
      const SidewallLaw::CordForce cord =
          wedge.law_.cord_force(chord_[i], wedge.reference_half_angle_[q], wedge.pressure_->at(time));
      force_[i] = cord.force;
      stiffness_[i] = cord.stiffness;
    }
  }
}

TIREFE_SIMD_CLONES void SidewallWedge::Batch::add_cords(const double* u, int q) {
  // On plain arrays, which the vectoriser sees apart.
  const int n = size();
  const double shape_a = 1.0 - kGaussPoints[q], shape_b = kGaussPoints[q];
  const double *offset_x = &reference_rim_x_[q * n], *offset_y = &reference_rim_y_[q * n];
  const double *reference_x = &reference_tread_x_[q * n], *reference_y = &reference_tread_y_[q * n];
  const double *cos_spin = cos_spin_.data(), *sin_spin = sin_spin_.data(), *spindle_x = spindle_x_.data(),
               *spindle_y = spindle_y_.data(), *switch_chord = switch_chord_.data(), *cord_length = cord_length_.data();
  double *rim_x = &rim_x_[q * n], *rim_y = &rim_y_[q * n], *cord_x = &cord_x_[q * n], *cord_y = &cord_y_[q * n];
  double *e_y_x = &e_y_x_[q * n], *e_y_y = &e_y_y_[q * n], *chord = &chord_[q * n], *cross = &cross_[q * n],
         *dot = &dot_[q * n], *ratio = &ratio_[q * n];
#pragma omp simd
  for (int e = 0; e < n; ++e) {
    const CordPoint p = cord_point(cos_spin[e], sin_spin[e], offset_x[e], offset_y[e], reference_x[e], reference_y[e],
                                   spindle_x[e], spindle_y[e], shape_a, shape_b, u + e, n);
    rim_x[e] = p.rim_x;
    rim_y[e] = p.rim_y;
    cord_x[e] = p.cord_x;
    cord_y[e] = p.cord_y;
    e_y_x[e] = p.e_y_x;
    e_y_y[e] = p.e_y_y;
    chord[e] = p.chord;
    cross[e] = p.cross;
    dot[e] = p.dot;
    const double length = p.chord;
    // A near-straight cord takes the law's linear continuation: its arch is not solved.
    ratio[e] = length < switch_chord[e] ? length / cord_length[e] : 0.5;
  }
}

TIREFE_SIMD_CLONES void SidewallWedge::Batch::add_cord_forces(int q) {
  const int n = size();
#pragma omp simd
  for (int e = 0; e < n; ++e) {
    const int i = q * n + e;
    const SidewallLaw::CordForce cord = arch_law(membrane_scale_[e], signed_bending_[e], cord_length_[e], chord_[i],
                                                 half_angle_[i], cos_half_[i], sin_half_[i], reference_half_angle_[i]);
    force_[i] = cord.force;
    stiffness_[i] = cord.stiffness;
  }
}

template <bool Tangent, bool Damped>
TIREFE_SIMD_CLONES void SidewallWedge::Batch::add_points(const BlockValues& values, const IntegratorFactors& f) {
  const int n = size();
  const double* u = values.displacement;
  const double* v = values.velocity;
  double* residual = residual_.data();
  double* tangent = tangent_.data();
#pragma omp simd
  for (int e = 0; e < n; ++e) {
    // The deformed tread chord l and its direction t.
    const double chord_x = tread_b_x_[e] + u[6 * n + e] - tread_a_x_[e] - u[3 * n + e];
    const double chord_y = tread_b_y_[e] + u[7 * n + e] - tread_a_y_[e] - u[4 * n + e];
    const double chord_length = std::sqrt(chord_x * chord_x + chord_y * chord_y);
    const double t[2] = {chord_x / chord_length, chord_y / chord_length};
    const double length_weight = kGaussWeight * chord_length;
    const double shear_stiffness = shear_stiffness_[e];
    const double c_r = Damped ? radial_damping_[e] : 0.0, c_t = Damped ? circumferential_damping_[e] : 0.0;
    const double spin_rate = v[2 * n + e];
    // B^T x for B = [I, rho_perp, -N_a I, 0, -N_b I, 0] has the rows x, rho_perp.x, -N_a x,
    // 0, -N_b x, 0: the quadrature sums the spindle rows, the spin row and the N-weighted
    // tread rows of the weighted traction (residual) and of its derivative J by the DOFs
    // (tangent, active columns 0, 1, 2, 3, 4, 6, 7), and the element vector and matrix are
    // written once from them.
    double spindle[2] = {0.0, 0.0}, spin = 0.0, tread_a[2] = {0.0, 0.0}, tread_b[2] = {0.0, 0.0};
    double spindle_rows[2][7] = {}, spin_row[7] = {}, rows_a[2][7] = {}, rows_b[2][7] = {}, spin_geometric = 0.0;
    // Fully unrolled (as are the loops over columns) so that the wedge loop vectorises.
#pragma GCC unroll 2
    for (int q = 0; q < kQuadraturePoints; ++q) {
      const int i = q * n + e;
      const double shape_a = 1.0 - kGaussPoints[q], shape_b = kGaussPoints[q];
      const double e_y[2] = {e_y_x_[i], e_y_y_[i]}, e_x[2] = {-e_y_y_[i], e_y_x_[i]};
      const double rho[2] = {rim_x_[i], rim_y_[i]}, perp[2] = {-rim_y_[i], rim_x_[i]};
      const double chord = chord_[i], force = force_[i];
      const double shear_force = shear_stiffness * shear_angle_[i];
      double elastic[2], damping[2] = {0.0, 0.0}, weighted[2], traction[2];
      for (int c = 0; c < 2; ++c) elastic[c] = force * e_y[c] + shear_force * e_x[c];
      double v_y = 0.0, v_x = 0.0;
      if (Damped) {
        // Tread point velocity relative to the rim's rigid motion (x_t - x_S = rho - P).
        const double arm[2] = {rho[0] - cord_x_[i], rho[1] - cord_y_[i]};
        const double relative[2] = {shape_a * v[3 * n + e] + shape_b * v[6 * n + e] - v[e] - spin_rate * -arm[1],
                                    shape_a * v[4 * n + e] + shape_b * v[7 * n + e] - v[n + e] - spin_rate * arm[0]};
        v_y = relative[0] * e_y[0] + relative[1] * e_y[1];
        v_x = relative[0] * e_x[0] + relative[1] * e_x[1];
        for (int c = 0; c < 2; ++c) damping[c] = -(c_r * v_y) * e_y[c] - (c_t * v_x) * e_x[c];
      }
      for (int c = 0; c < 2; ++c) {
        weighted[c] = length_weight * (f.force_stiffness * elastic[c] + f.force_damping * damping[c]);
        spindle[c] += weighted[c];
        tread_a[c] += shape_a * weighted[c];
        tread_b[c] += shape_b * weighted[c];
      }
      spin += perp[0] * weighted[0] + perp[1] * weighted[1];
      if (!Tangent) continue;

      // G = cK (F' e_y e_y^T + ((F + k_gamma) e_x - S e_y) e_x^T / L) (+ damping).
      const double stiffness = stiffness_[i];
      double G[2][2], spin_column[2];
      for (int r = 0; r < 2; ++r) {
        traction[r] = f.tangent_stiffness * elastic[r] + f.force_damping * damping[r];
        const double w = (force + shear_stiffness) * e_x[r] - shear_force * e_y[r];
        for (int c = 0; c < 2; ++c) G[r][c] = f.tangent_stiffness * (stiffness * e_y[r] * e_y[c] + w * e_x[c] / chord);
        spin_column[r] = -f.tangent_stiffness * shear_stiffness * e_x[r];
      }
      if (Damped) {
        double C_d[2][2];
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c) C_d[r][c] = c_r * e_y[r] * e_y[c] + c_t * e_x[r] * e_x[c];
        for (int r = 0; r < 2; ++r) {
          const double rate = -(c_r - c_t) * (v_x * e_y[r] + v_y * e_x[r]);
          const double turned[2] = {C_d[r][1], -C_d[r][0]};  // C_d k x
          for (int c = 0; c < 2; ++c) G[r][c] += f.force_damping * (rate * e_x[c] / chord - spin_rate * turned[c]);
          spin_column[r] -= f.force_damping * spin_rate * (C_d[r][0] * rho[0] + C_d[r][1] * rho[1]);
          for (int c = 0; c < 2; ++c) G[r][c] += f.tangent_damping * C_d[r][c];
          spin_column[r] -= (f.tangent_damping * c_t * chord) * e_x[r];
        }
      }
      // J = l w_q (G B + spin_column e_theta^T) + w_q traction dl/du on the active columns.
      double J[2][7];
      for (int r = 0; r < 2; ++r) {
        const double W0 = length_weight * G[r][0], W1 = length_weight * G[r][1];
        const double chord_force = kGaussWeight * traction[r];
        J[r][0] = W0;
        J[r][1] = W1;
        J[r][2] = W0 * perp[0] + W1 * perp[1] + length_weight * spin_column[r];
        J[r][3] = -shape_a * W0 - chord_force * t[0];
        J[r][4] = -shape_a * W1 - chord_force * t[1];
        J[r][5] = -shape_b * W0 + chord_force * t[0];
        J[r][6] = -shape_b * W1 + chord_force * t[1];
      }
#pragma GCC unroll 7
      for (int c = 0; c < 7; ++c) {
        for (int r = 0; r < 2; ++r) {
          spindle_rows[r][c] += J[r][c];
          rows_a[r][c] += shape_a * J[r][c];
          rows_b[r][c] += shape_b * J[r][c];
        }
        spin_row[c] += perp[0] * J[0][c] + perp[1] * J[1][c];
      }
      spin_geometric -= length_weight * (rho[0] * traction[0] + rho[1] * traction[1]);  // d rho_perp/d theta_S = -rho
    }
    // residual = (spindle, spin, -tread_a, 0, -tread_b, 0); the matrix likewise by rows.
    for (int c = 0; c < 2; ++c) {
      residual[c * n + e] = spindle[c];
      residual[(3 + c) * n + e] = -tread_a[c];
      residual[(6 + c) * n + e] = -tread_b[c];
    }
    residual[2 * n + e] = spin;
    if (!Tangent) continue;
    spin_row[2] += spin_geometric;
#pragma GCC unroll 7
    for (int c = 0; c < 7; ++c) {
      const int column = kActiveDofs[c];
      for (int r = 0; r < 2; ++r) {
        tangent[(r * kDofs + column) * n + e] = spindle_rows[r][c];
        tangent[((3 + r) * kDofs + column) * n + e] = -rows_a[r][c];
        tangent[((6 + r) * kDofs + column) * n + e] = -rows_b[r][c];
      }
      tangent[(2 * kDofs + column) * n + e] = spin_row[c];
    }
  }
}

void SidewallWedge::Batch::evaluate(const BlockValues& values, const EvaluationContext& context, bool with_tangent) {
  const IntegratorFactors& f = context.factors;
  const bool damped = damped_ && (f.force_damping != 0.0 || (with_tangent && f.tangent_damping != 0.0));
  solve_cords(values, context.time);
  if (with_tangent)
    damped ? add_points<true, true>(values, f) : add_points<true, false>(values, f);
  else
    damped ? add_points<false, true>(values, f) : add_points<false, false>(values, f);
}

ElementEnergy SidewallWedge::energy(const LocalState<kDofs>&, const History&) const { return {}; }

}  // namespace tirefe
