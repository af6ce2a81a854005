// SidewallWedge: the sidewall part of one wedge of the ring tire (docs/model.md section 3,
// paper eqs. 1-13). Nodes: spindle S, tread nodes a and b (counter-clockwise); only
// the spindle rotation theta_S among the rotations enters. Reference data: X_S, X_a, X_b.
//
// At a point xi in [0, 1] of the tread chord (N_a = 1 - xi, N_b = xi):
//   tread point  x_t = N_a x_a + N_b x_b,                   x = X + u
//   rim point    x_r = x_S + rho,  rho = R(theta_S) r_rim e_r,
//                e_r = (X_t - X_S)/|X_t - X_S| (the reference cord is radial)
//   cord         P = x_r - x_t (eq. 5),  L = |P| (eq. 6),  e_y = P/L points from the
//                tread toward the rim (eq. 7),  e_x = k x e_y (eq. 8).
// The inextensible cord of length l_sw is a circular arch over the chord L; with the
// half-angle alpha = pi/2 - theta of the arc (theta the meridian angle of eq. 1):
//   l_sw sin(alpha) = L alpha                    (eq. 1, alpha in (0, pi])
//   r = L / (2 cos theta) = l_sw / (2 alpha)     (eq. 2, finite for every alpha > 0)
// Force per unit deformed tread length on the tread (eq. 9, with n_sw sidewalls):
//   T_t = F(L) e_y + k_gamma gamma e_x
//   F   = n_sw p r sin(theta) + s k_sw (1/r^2 - 1/(r r0)) sin(theta)
//       = n_sw p l_sw cos(alpha) / (2 alpha) + s k_sw (4/l_sw^2) alpha (alpha - alpha0) cos(alpha)
// F > 0 pulls the tread toward the rim; n_sw p r sin(theta) = n_sw p (L/2) tan(theta).
// s = bending_sign (+1: eq. 9 as printed; -1: the physical bending direction); r0 and
// alpha0 come from the reference cord at the same point; gamma is the angle from the
// rotated reference cord R(theta_S)(-e_r) to e_y, counter-clockwise (gamma0 = 0 since
// the reference cord itself is the zero). The spindle takes -T_t at the rim point:
// force -T_t and moment k.(rho x (-T_t)) (eqs. 10-11).
//
// Near-straight cords: F grows like p l_sw/(2 alpha) and dF/dL like 1.5 n_sw p/alpha^3
// as alpha -> 0, and L > l_sw has no arch at all. For L beyond the switch chord
// L* = l_sw sin(alpha*)/alpha* (alpha* = straight_cord_half_angle) F continues linearly,
// F(L) = F(L*) + F'(L*) (L - L*): a stretchable cord whose axial stiffness per unit
// length is the arch's own stiffness at the switch (force and tangent are continuous).
//
// Damping (paper section 2.2.4): dashpots per unit length on the velocity of the tread
// point relative to the rim's rigid motion extended to it,
//   v = v_t - v_S - omega_S k x (x_t - x_S),   D = -c_r (v.e_y) e_y - c_t (v.e_x) e_x,
// i.e. on the rates of the cord length and of gamma (v.e_y = -dL/dt, v.e_x = -L dgamma/dt):
// a wedge spinning rigidly is not damped.
//
// Weak form (eqs. 12-13): with dP = B du (B the 2x9 kinematic matrix of P), the
// residual is  sum_q w_q l B^T (wK T_t + wC D),  l the deformed chord length |x_b - x_a|
// (two-point Gauss rule on the chord, weights 1/2). The consistent tangent is derived
// by hand in sidewall.cpp. The element has no strain energy (energy() returns zero):
// the pressure term is a follower force and k_gamma gamma e_x is not a gradient when
// L varies. docs/sidewall.md has the conventions and units.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <memory>
#include <vector>

#include "core/element.hpp"
#include "elements/pressure_schedule.hpp"

namespace tirefe {

/// The circular arch over a chord L of an inextensible cord of length l_sw (eq. 1).
struct ArchShape {
  double half_angle;                        // alpha = pi/2 - theta, in (0, pi]
  double dhalf_angle_dchord;                // d alpha / d L [1/m], from eq. 1 by implicit differentiation
  double meridian_angle() const;            // theta of eqs. 1-2, in [-pi/2, pi/2)
  double radius(double cord_length) const;  // r = l_sw / (2 alpha)
};

/// Solves eq. 1 for 0 <= chord < cord_length by safeguarded Newton on the half-angle
/// (to round-off); throws std::domain_error outside that range (no arch exists).
ArchShape solve_arch(double chord, double cord_length);

/// The arch's half-angle alpha with its cosine and sine, for a chord ratio L / l_sw.
struct ArchSolution {
  double half_angle, cos_half, sin_half;
};
/// The half-angles of 'count' arches at once (ratios in [0, 1)), vectorised across them:
/// the same numbers, bit for bit, as one arch at a time (solve_arch's root).
void solve_half_angles(const double* ratio, int count, double* half_angle, double* cos_half, double* sin_half);

struct SidewallProperties {
  double rim_radius = 0.0;                // r_rim [m]
  double cord_length = 0.0;               // l_sw [m]
  int sidewall_count = 2;                 // n_sw on the pressure term
  double bending_stiffness = 0.0;         // k_sw [N m], both sidewalls together
  double bending_sign = 1.0;              // s: +1 eq. 9 as printed, -1 the physical direction
  double shear_stiffness = 0.0;           // k_gamma [N/m per rad], both sidewalls together
  double radial_damping = 0.0;            // c_r [N s/m^2], along the cord
  double circumferential_damping = 0.0;   // c_t [N s/m^2], across the cord
  double straight_cord_half_angle = 0.1;  // alpha* [rad]: the arch law holds for alpha >= alpha*

  /// Throws ModelError naming the first non-physical value.
  void check() const;
};

/// The section law of the sidewall: force F along the cord per unit tread length as a
/// function of the chord L, with the regularisation of near-straight cords.
class SidewallLaw {
 public:
  struct CordForce {
    double force;      // F [N/m], > 0 pulls the tread toward the rim
    double stiffness;  // dF/dL [N/m^2]
  };

  explicit SidewallLaw(const SidewallProperties& properties);

  /// alpha0 of a reference chord; throws ModelError unless 0 < chord < switch_chord().
  double reference_half_angle(double chord) const;
  CordForce cord_force(double chord, double reference_half_angle, double pressure) const;
  /// cord_force of a chord below switch_chord() whose arch is solved already.
  CordForce arch_cord_force(double chord, const ArchSolution& arch, double reference_half_angle, double pressure) const;
  /// L* = l_sw sin(alpha*)/alpha*, where the linear continuation takes over.
  double switch_chord() const { return switch_chord_; }
  const SidewallProperties& properties() const { return properties_; }
  /// The membrane term's factor n_sw p l_sw / 2 [N], and the bending term's s k_sw 4 / l_sw^2.
  double membrane_scale(double pressure) const {
    return 0.5 * properties_.sidewall_count * pressure * properties_.cord_length;
  }
  double signed_bending() const { return signed_bending_; }

 private:
  SidewallProperties properties_;
  double signed_bending_;  // s k_sw (4 / l_sw^2) [N/m]
  double switch_chord_, switch_cos_, switch_sin_, switch_dhalf_angle_dchord_;
};

class SidewallWedge : public KernelShape<3> {
 public:
  static constexpr int kQuadraturePoints = 2;
  static constexpr KernelTraits traits() {
    KernelTraits traits;
    traits.reads_acceleration = false;
    traits.stores_energy = false;  // energy() is zero (above)
    traits.idle_dofs = {5, 8};     // the tread rotations
    return traits;
  }

  /// Reference positions of the spindle and of the two tread nodes (counter-clockwise).
  SidewallWedge(const Eigen::Vector2d& spindle, const Eigen::Vector2d& tread_a, const Eigen::Vector2d& tread_b,
                const SidewallProperties& properties, std::shared_ptr<const PressureSchedule> pressure);

  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History& committed,
                History& trial, Vector& residual, Matrix* tangent) const;
  /// Zero: the sidewall forces derive from no potential (see the file comment).
  ElementEnergy energy(const LocalState<kDofs>& local, const History& history) const;

  /// Cord length L and shear angle gamma at quadrature point q, for output and tests.
  struct CordState {
    double chord, shear_angle;
  };
  CordState cord_state(const Vector& displacement, int q) const;
  /// The block's batch path (element.hpp): every wedge at once; evaluate() is its block of one.
  class Batch;
  const SidewallLaw& law() const { return law_; }
  double reference_half_angle(int q) const { return reference_half_angle_[q]; }

 private:
  SidewallLaw law_;
  std::shared_ptr<const PressureSchedule> pressure_;
  Eigen::Vector2d spindle_, tread_a_, tread_b_;
  // Per quadrature point: reference tread point, reference rim offset r_rim e_r, alpha0.
  std::array<Eigen::Vector2d, kQuadraturePoints> reference_tread_, reference_rim_offset_;
  std::array<double, kQuadraturePoints> reference_half_angle_;
};

/// Wedges over structure-of-arrays data: passes vectorised across the wedges' points find
/// the cords, solve their arches and take their force law (the shear angle's arcsine, one
/// sine and cosine per spindle angle and a near-straight cord's law are scalar passes);
/// then a pass vectorised across wedges forms the weighted tractions, their derivatives
/// and the element vectors and matrices. It is the wedge's one implementation: evaluate()
/// runs it on a block of one (core/batch_of_one.hpp).
class SidewallWedge::Batch {
 public:
  explicit Batch(const std::vector<SidewallWedge>& wedges);
  /// The batch of other wedges (without allocating when their number is the same).
  void assign(const std::vector<SidewallWedge>& wedges);
  int size() const { return static_cast<int>(wedges_.size()); }
  void evaluate(const BlockValues& values, const EvaluationContext& context, bool with_tangent);
  const double* residual() const { return residual_.data(); }
  const double* tangent() const { return tangent_.data(); }

 private:
  /// The cord at both points of every wedge: directions, chord, force law, shear angle.
  void solve_cords(const BlockValues& values, double time);
  /// The cords at point q of every wedge, without gamma.
  void add_cords(const double* displacement, int q);
  /// The arch branch of the force law at point q of every wedge (near-straight cords are
  /// solve_cords' to correct).
  void add_cord_forces(int q);
  /// The element vectors (and matrices) from the weighted tractions (and their derivatives).
  template <bool Tangent, bool Damped>
  void add_points(const BlockValues& values, const IntegratorFactors& f);

  std::vector<SidewallWedge> wedges_;
  // Per wedge: reference tread nodes, k_gamma, c_r, c_t.
  std::vector<double> tread_a_x_, tread_a_y_, tread_b_x_, tread_b_y_, shear_stiffness_, radial_damping_,
      circumferential_damping_;
  bool damped_ = false;  // some wedge has dashpots
  // Per wedge and point [q * size + e]: rho, P, e_y, L, F, dF/dL, gamma.
  std::vector<double> rim_x_, rim_y_, cord_x_, cord_y_, e_y_x_, e_y_y_, chord_, force_, stiffness_, shear_angle_;
  // Per wedge and point: the reference tread point, rim offset and alpha0; the cross and
  // dot products of the turned reference cord with e_y (for gamma); the arch's chord ratio
  // L / l_sw and its solution.
  std::vector<double> reference_tread_x_, reference_tread_y_, reference_rim_x_, reference_rim_y_, reference_half_angle_,
      cross_, dot_, ratio_, half_angle_, cos_half_, sin_half_;
  // Per wedge: the spindle's reference position, the law's constants; the spin's cosine
  // and sine and the pressure terms of the evaluation.
  std::vector<double> spindle_x_, spindle_y_, cord_length_, switch_chord_, rim_radius_, signed_bending_, cos_spin_,
      sin_spin_, membrane_scale_;
  std::vector<double> residual_, tangent_;  // [k * size + e]
};

}  // namespace tirefe
