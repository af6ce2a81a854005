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

  IntegratorFactors factors(double step) const;
  /// Weight of the new (t_{n+1}) and old (t_n) force levels: 1 + alpha and -alpha.
  double new_force_weight() const { return 1.0 + alpha_; }
  double old_force_weight() const { return -alpha_; }

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

}  // namespace tirefe
