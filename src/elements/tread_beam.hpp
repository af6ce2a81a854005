// TreadBeam: a geometrically exact plane beam (Simo-Reissner), two nodes with
// (u_x, u_y, theta_z), used for the tire's tread (belt) and for test structures.
//
// Kinematics, with x = X + u, the reference length L0 and reference angle phi0:
//   x' = (x_b - x_a) / L0,  beta = phi0 + (theta_a + theta_b) / 2,
//   t = (cos beta, sin beta),  n = (-sin beta, cos beta),
//   axial strain eps = x'.t - 1,  shear strain gam = x'.n,  curvature kap = (theta_b - theta_a) / L0.
// Section law: N = EA eps, V = GA_s gam, M = EI kap. All strains are sampled at the
// midpoint (one-point quadrature), which removes shear locking for linear interpolation.
// Energy L0 (EA eps^2 + GA gam^2 + EI kap^2) / 2; the residual is its gradient and the
// tangent its (symmetric) Hessian, including the geometric terms N d2eps + V d2gam.
// Inertia: consistent mass of rho*A (translations) and rho*I (rotation), linear shape
// functions. Damping: a bending moment c_kappa * d(kap)/dt (curvature-rate damping).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "core/element.hpp"

namespace tirefe {

struct BeamSection {
  double axial_stiffness = 0.0;            // EA [N]
  double shear_stiffness = 0.0;            // GA_s [N]
  double bending_stiffness = 0.0;          // EI [N m^2]
  double mass_per_length = 0.0;            // rho A [kg/m]
  double rotary_inertia_per_length = 0.0;  // rho I [kg m]
  double curvature_damping = 0.0;          // c_kappa [N m^2 s]

  /// Throws ModelError naming the first non-physical value.
  void check() const;
};

class TreadBeam : public KernelShape<2> {
 public:
  TreadBeam(const Eigen::Vector2d& start, const Eigen::Vector2d& end, const BeamSection& section);

  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History& committed,
                History& trial, Vector& residual, Matrix* tangent) const;
  ElementEnergy energy(const LocalState<kDofs>& local, const History& history) const;
  /// M x with the consistent mass of linear shape functions (M a: the inertia forces).
  Vector mass_times(const Vector& x) const;

  struct Strains {
    double axial, shear, curvature;
  };
  Strains strains(const Vector& displacement) const;
  const BeamSection& section() const { return section_; }
  /// The block's batch path (element.hpp): every beam at once; evaluate() and energy() are
  /// its block of one.
  class Batch;

 private:
  BeamSection section_;
  double length_;
  double reference_angle_;
  Eigen::Vector2d reference_direction_;  // (cos phi0, sin phi0)
};

/// Beams over structure-of-arrays data: one loop vectorised across beams forms the
/// strains (the sine and cosine of beta inline, sine_cosine.hpp), the section forces and
/// the element vectors and matrices: the beam's one implementation (core/batch_of_one.hpp).
class TreadBeam::Batch {
 public:
  explicit Batch(const std::vector<TreadBeam>& beams);
  /// The batch of other beams (without allocating when their number is the same).
  void assign(const std::vector<TreadBeam>& beams);
  int size() const { return count_; }
  void evaluate(const BlockValues& values, const EvaluationContext& context, bool with_tangent);
  const double* residual() const { return residual_.data(); }
  const double* tangent() const { return tangent_.data(); }
  /// The beams' strain and kinetic energy, summed: energy()'s terms.
  ElementEnergy energy(const BlockValues& values) const;

 private:
  template <bool Tangent>
  void evaluate_beams(const BlockValues& values, const IntegratorFactors& f);

  int count_ = 0;
  // Per beam: L0, phi0, (cos phi0, sin phi0), EA, GA_s, EI, rho A, rho I, c_kappa.
  std::vector<double> length_, reference_angle_, direction_x_, direction_y_, axial_, shear_, bending_, mass_,
      rotary_inertia_, curvature_damping_;
  std::vector<double> residual_, tangent_;  // [k * size + e]
};

}  // namespace tirefe
