// TimeScheme: one member of the integrators' family (quasi-static, or generalized-alpha and
// its presets Newmark, HHT-alpha, WBZ-alpha), the step formulas an Analysis asks for. The
// schemes are in this folder; the deck's registry of presets is in integrator.cpp;
// Integrator is the value callers hold.
//
// Convention (Chung & Hulbert 1993; quasi-static drops M and C):
//   M a_{n+1-alpha_m} + g(u_{n+1-alpha_f}, v_{n+1-alpha_f}) = F(t_{n+1-alpha_f}),
//   x_{n+1-alpha} = (1 - alpha) x_{n+1} + alpha x_n,      g = f_int(u) + C v,
// each force level weighted as a whole (g_{n+1-alpha_f} = (1-alpha_f) g_{n+1} + alpha_f g_n,
// as HHT does), with Newmark's update formulas
//   u_{n+1} = u_n + h v_n + h^2 [(1/2 - beta) a_n + beta a_{n+1}],
//   v_{n+1} = v_n + h [(1 - gamma) a_n + gamma a_{n+1}].
// Newmark is alpha_m = alpha_f = 0, HHT-alpha alpha_m = 0 and alpha_f = -alpha.
// Elements see only the weights and tangent factors (element.hpp):
//   w = (1-alpha_f, 1-alpha_f, 1-alpha_m),
//   c = (1-alpha_f, (1-alpha_f) gamma/(beta h), (1-alpha_m)/(beta h^2)).
// Predictors (the start of each step's Newton iterations):
//   SameAcceleration  a_{n+1} = a_n: follows smooth motion (a rolling tire, a car body);
//   ZeroAcceleration  a_{n+1} = 0, u and v from the Newmark formulas: better where
//                     accelerations jump from step to step, as at the nodes of a contact
//                     patch rolling at speed, whose impact accelerations the first one
//                     would extrapolate into the road;
//   SameDisplacement  u_{n+1} = u_n.
#pragma once

#include <optional>
#include <string>

#include "core/element.hpp"
#include "core/state.hpp"

namespace tirefe {

enum class Predictor { SameAcceleration, ZeroAcceleration, SameDisplacement };

/// What names a scheme in a checkpoint (attributes integrator_kind, beta, gamma, alpha,
/// alpha_m of docs/restart.md): a restore continues only with the same scheme.
struct SchemeRecord {
  int kind = 0;  // each scheme's own number, never reused: files already written hold it
  double beta = 0.0, gamma = 0.0;
  double alpha = 0.0;    // -alpha_f: HHT's alpha
  double alpha_m = 0.0;  // the inertia's
  bool operator==(const SchemeRecord& other) const {
    return kind == other.kind && beta == other.beta && gamma == other.gamma && alpha == other.alpha &&
           alpha_m == other.alpha_m;
  }
  bool operator!=(const SchemeRecord& other) const { return !(*this == other); }
};

/// The rate changes of a Newton increment du of one DOF over a step: v += velocity_factor
/// du, a += du / acceleration_divisor (dynamic schemes). Taken once per iteration, applied
/// per DOF inline.
struct RateCorrection {
  bool dynamic = false;
  double velocity_factor = 0.0, acceleration_divisor = 1.0;
  void apply(int dof, double increment, State& trial) const {
    trial.displacement[dof] += increment;
    if (dynamic) {
      trial.velocity[dof] += velocity_factor * increment;
      trial.acceleration[dof] += increment / acceleration_divisor;
    }
  }
};

class TimeScheme {
 public:
  virtual ~TimeScheme() = default;

  virtual std::string name() const = 0;
  virtual bool is_dynamic() const = 0;
  virtual SchemeRecord record() const = 0;
  /// alpha when the scheme is HHT-alpha (Newmark average acceleration: alpha = 0), none otherwise.
  virtual std::optional<double> hht_alpha() const = 0;

  /// The weights and tangent factors of the step equations with step size h.
  virtual IntegratorFactors factors(double step) const = 0;
  /// The physical residual M a + C v + f_int (f_int alone quasi-statically), no tangent.
  virtual IntegratorFactors physical_residual_factors() const = 0;
  /// Weights of the new (t_{n+1}) and old (t_n) force levels; they add up to one.
  virtual double new_force_weight() const { return 1.0; }
  virtual double old_force_weight() const { return 0.0; }
  /// Weight alpha_m of the old inertia force M a_n (that of M a_{n+1} is 1 - alpha_m).
  virtual double old_inertia_weight() const { return 0.0; }

  /// Predicts the state at t_n + step from the committed state (every DOF).
  virtual void predict(const State& committed, double step, Predictor predictor, State& trial) const = 0;
  /// Velocity and acceleration of one DOF whose displacement is known at t_{n+1}.
  virtual void update_rates(const State& committed, double step, int dof, State& trial) const = 0;
  virtual RateCorrection rate_correction(double step) const = 0;
  /// The displacement at t_{n+1} of a DOF with the rates (u, v, a) at t_n whose velocity
  /// at t_{n+1} is given, and its derivative by that velocity (a host driving by velocity).
  /// ModelError for a scheme without velocities.
  virtual double displacement_for_velocity(double u, double v, double a, double new_velocity, double step) const = 0;
  virtual double displacement_per_velocity(double step) const = 0;
};

}  // namespace tirefe
