// Integrator: the quasi-static, Newmark and HHT-alpha step formulas.
//
// Convention (Hilber-Hughes-Taylor 1977; Newmark is alpha = 0, quasi-static drops M, C):
//   M a_{n+1} + (1+alpha) g(u_{n+1}, v_{n+1}) - alpha g(u_n, v_n)
//       = (1+alpha) F(t_{n+1}) - alpha F(t_n),           g = f_int(u) + C v,
//   u_{n+1} = u_n + h v_n + h^2 [(1/2 - beta) a_n + beta a_{n+1}],
//   v_{n+1} = v_n + h [(1 - gamma) a_n + gamma a_{n+1}],
// with alpha in [-1/3, 0], beta = (1-alpha)^2/4, gamma = (1-2 alpha)/2 for HHT.
// Elements see only the weights and tangent factors (element.hpp):
//   w = (1+alpha, 1+alpha, 1),  c = ((1+alpha), (1+alpha) gamma/(beta h), 1/(beta h^2)).
// Predictors (the start of each step's Newton iterations):
//   SameAcceleration  a_{n+1} = a_n: follows smooth motion (a rolling tire, a car body);
//   ZeroAcceleration  a_{n+1} = 0, u and v from the Newmark formulas: better where
//                     accelerations jump from step to step, as at the nodes of a contact
//                     patch rolling at speed, whose impact accelerations the first one
//                     would extrapolate into the road;
//   SameDisplacement  u_{n+1} = u_n.
#pragma once

#include <string>
#include <vector>

#include "core/element.hpp"
#include "core/state.hpp"

namespace tirefe {

class Integrator {
 public:
  enum class Kind { QuasiStatic, Newmark, Hht };
  enum class Predictor { SameAcceleration, ZeroAcceleration, SameDisplacement };

  static Integrator quasi_static() { return Integrator(Kind::QuasiStatic, 0.25, 0.5, 0.0); }
  /// Newmark(beta, gamma), 1/2 <= gamma <= 1, gamma/2 <= beta <= 1 (unconditionally
  /// stable); average acceleration by default. ModelError with the ranges otherwise.
  static Integrator newmark(double beta = 0.25, double gamma = 0.5);
  /// HHT-alpha with alpha in [-1/3, 0] (ModelError with the range otherwise).
  static Integrator hht(double alpha);

  Kind kind() const { return kind_; }
  bool is_dynamic() const { return kind_ != Kind::QuasiStatic; }
  std::string name() const;
  double beta() const { return beta_; }
  double gamma() const { return gamma_; }
  double alpha() const { return alpha_; }
  Predictor predictor() const { return predictor_; }
  /// This scheme with another predictor (the default keeps the acceleration).
  Integrator with_predictor(Predictor predictor) const {
    Integrator copy = *this;
    copy.predictor_ = predictor;
    return copy;
  }

  /// The weights and tangent factors of the step equations with step size h.
  IntegratorFactors factors(double step) const;
  /// g = f_int + C v alone (HHT's old and new internal forces), no tangent.
  static IntegratorFactors internal_force_factors();
  /// The physical residual M a + C v + f_int (f_int alone quasi-statically), no tangent:
  /// at prescribed DOFs, with the loads taken off, the support reactions.
  IntegratorFactors physical_residual_factors() const;
  /// Residual g = f_int + C v with the tangent M: the initial acceleration's M a = F - g.
  static IntegratorFactors initial_acceleration_factors();

  /// Weight of the new (t_{n+1}) and old (t_n) force levels: 1 + alpha and -alpha.
  double new_force_weight() const { return 1.0 + alpha_; }
  double old_force_weight() const { return -alpha_; }
  /// True when the step equations hold the old forces (HHT): g_n must be known.
  bool weights_old_forces() const { return old_force_weight() != 0.0; }
  /// Adds the loads to the element forces of the step equations (element forces weighted
  /// by factors()): - (1+alpha) F_{n+1} - alpha (g_n - F_n).
  void add_load_terms(const Eigen::VectorXd& external_new, const Eigen::VectorXd& internal_old,
                      const Eigen::VectorXd& external_old, Eigen::VectorXd& residual) const {
    residual -= new_force_weight() * external_new;
    if (weights_old_forces()) residual += old_force_weight() * (internal_old - external_old);
  }
  /// Turns the converged residual of the step equations into the physical one
  /// M a + g_{n+1} - F_{n+1}, whose prescribed entries are the reactions. HHT's residual
  /// differs from it by alpha [(g_{n+1} - F_{n+1}) - (g_n - F_n)]: 'internal' holds g_n on
  /// entry and g_{n+1} on return, from one call of assemble_internal(internal) (which the
  /// next step's weighting needs anyway). Nothing to do without old forces.
  template <class AssembleInternal>
  void to_physical_residual(const Eigen::VectorXd& external_old, const Eigen::VectorXd& external_new,
                            Eigen::VectorXd& internal, AssembleInternal&& assemble_internal,
                            Eigen::VectorXd& residual) const {
    if (!weights_old_forces()) return;
    residual += alpha_ * (internal - external_old);
    assemble_internal(internal);
    residual -= alpha_ * (internal - external_new);
  }

  /// Predicts the state at t_n + step from the committed state (every DOF).
  void predict(const State& committed, double step, State& trial) const;
  /// Velocity and acceleration of one DOF whose displacement is known at t_{n+1}
  /// (a prescribed DOF, or a free DOF after a Newton correction).
  void update_rates(const State& committed, double step, int dof, State& trial) const;
  /// Adds a Newton increment du to a free DOF with its consistent rate changes.
  void correct(double step, int dof, double increment, State& trial) const {
    trial.displacement[dof] += increment;
    if (is_dynamic()) {
      trial.velocity[dof] += gamma_ / (beta_ * step) * increment;
      trial.acceleration[dof] += increment / (beta_ * step * step);
    }
  }

 private:
  Integrator(Kind kind, double beta, double gamma, double alpha)
      : kind_(kind), beta_(beta), gamma_(gamma), alpha_(alpha) {}

  Kind kind_;
  double beta_, gamma_, alpha_;
  Predictor predictor_ = Predictor::SameAcceleration;
};

/// The deck's integrators by name (model:integrator{ type = ... }): one entry per scheme,
/// made from the parameters the deck gives.
struct IntegratorParameters {
  double beta = 0.25, gamma = 0.5, alpha = -0.05;
  Integrator::Predictor predictor = Integrator::Predictor::SameAcceleration;
};
struct IntegratorScheme {
  const char* name;
  Integrator (*make)(const IntegratorParameters& parameters);
};
const std::vector<IntegratorScheme>& integrator_schemes();
std::vector<std::string> integrator_names();
/// ModelError naming the known schemes for an unknown name.
Integrator make_integrator(const std::string& name, const IntegratorParameters& parameters);
/// The predictors' deck names, in Predictor's order.
std::vector<std::string> predictor_names();
Integrator::Predictor predictor_named(const std::string& name);

}  // namespace tirefe
