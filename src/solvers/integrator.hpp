// Integrator: the time scheme an Analysis steps with, as a cheap value (a shared, immutable
// TimeScheme and the predictor that starts each step's Newton iterations). The schemes
// and their formulas are in integrators/ (time_scheme.hpp: the convention); the deck names
// the generalized-alpha presets in one registry, alpha_presets().
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/element.hpp"
#include "core/state.hpp"
#include "solvers/integrators/generalized_alpha.hpp"

namespace tirefe {

class Integrator {
 public:
  using Predictor = tirefe::Predictor;

  explicit Integrator(std::shared_ptr<const TimeScheme> scheme) : scheme_(std::move(scheme)) {}

  static Integrator quasi_static();
  /// Newmark(beta, gamma), 1/2 <= gamma <= 1, gamma/2 <= beta <= 1 (unconditionally
  /// stable); average acceleration by default. ModelError with the ranges otherwise.
  static Integrator newmark(double beta = 0.25, double gamma = 0.5);
  /// HHT-alpha with alpha in [-1/3, 0] (ModelError with the range otherwise).
  static Integrator hht(double alpha);
  /// Generalized-alpha (Chung-Hulbert) with rho_inf in [0, 1] (ModelError otherwise).
  static Integrator generalized_alpha(double rho_inf);
  /// HHT-alpha, or Newmark average acceleration for alpha = 0 (a vehicle's schemes).
  static Integrator hht_or_average_acceleration(double alpha) { return alpha == 0.0 ? newmark() : hht(alpha); }

  const TimeScheme& scheme() const { return *scheme_; }
  bool is_dynamic() const { return scheme_->is_dynamic(); }
  std::string name() const { return scheme_->name(); }
  /// The scheme and its parameters as a checkpoint records them.
  SchemeRecord record() const { return scheme_->record(); }
  /// Whether another integrator steps with the same scheme and parameters (predictors aside).
  bool same_scheme(const Integrator& other) const { return record() == other.record(); }
  /// alpha of an HHT-alpha scheme (Newmark average acceleration: 0), none otherwise.
  std::optional<double> hht_alpha() const { return scheme_->hht_alpha(); }
  /// The Newmark parameters of the rate formulas, HHT's alpha (-alpha_f) and alpha_m
  /// (quasi-static: average acceleration's, unused).
  double beta() const { return record().beta; }
  double gamma() const { return record().gamma; }
  double alpha() const { return record().alpha; }
  double alpha_m() const { return record().alpha_m; }
  Predictor predictor() const { return predictor_; }
  /// This scheme with another predictor (the default keeps the acceleration).
  Integrator with_predictor(Predictor predictor) const {
    Integrator copy = *this;
    copy.predictor_ = predictor;
    return copy;
  }

  /// The weights and tangent factors of the step equations with step size h.
  IntegratorFactors factors(double step) const { return scheme_->factors(step); }
  /// g = f_int + C v alone (HHT's old and new internal forces), no tangent.
  static IntegratorFactors internal_force_factors();
  /// The physical residual M a + C v + f_int (f_int alone quasi-statically), no tangent:
  /// at prescribed DOFs, with the loads taken off, the support reactions.
  IntegratorFactors physical_residual_factors() const { return scheme_->physical_residual_factors(); }
  /// Residual g = f_int + C v with the tangent M: the initial acceleration's M a = F - g.
  static IntegratorFactors initial_acceleration_factors();

  /// Weight of the new (t_{n+1}) and old (t_n) force levels: 1 - alpha_f and alpha_f
  /// (HHT: 1 + alpha and -alpha); the old inertia force's, alpha_m.
  double new_force_weight() const { return scheme_->new_force_weight(); }
  double old_force_weight() const { return scheme_->old_force_weight(); }
  double old_inertia_weight() const { return scheme_->old_inertia_weight(); }
  /// True when the step equations hold old forces (HHT, generalized-alpha): g_n, and M a_n
  /// for alpha_m != 0, must be known.
  bool weights_old_forces() const { return old_force_weight() != 0.0 || old_inertia_weight() != 0.0; }
  /// Adds the loads and the old levels to the element forces of the step equations
  /// (element forces weighted by factors()): - w_new F_{n+1} + w_old (g_n - F_n) + alpha_m M a_n.
  void add_load_terms(const Eigen::VectorXd& external_new, const Eigen::VectorXd& internal_old,
                      const Eigen::VectorXd& inertia_old, const Eigen::VectorXd& external_old,
                      Eigen::VectorXd& residual) const {
    residual -= new_force_weight() * external_new;
    const double old_weight = old_force_weight(), inertia_weight = old_inertia_weight();
    if (old_weight != 0.0) residual += old_weight * (internal_old - external_old);
    if (inertia_weight != 0.0) residual += inertia_weight * inertia_old;
  }
  /// Turns the converged residual of the step equations into the physical one
  /// M a + g_{n+1} - F_{n+1}, whose prescribed entries are the reactions. With weights
  /// adding up to one it differs from it by
  /// w_old [(g_n - F_n) - (g_{n+1} - F_{n+1})] + alpha_m (M a_n - M a_{n+1}):
  /// 'internal' and 'inertia' hold g_n and M a_n on entry and g_{n+1} and M a_{n+1} on
  /// return, from one call of assemble(internal, inertia) made when the old levels are
  /// off the residual (the next step's weighting needs them anyway; 'inertia' only for
  /// alpha_m != 0). Nothing to do without old forces.
  template <class AssembleNewLevel>
  void to_physical_residual(const Eigen::VectorXd& external_old, const Eigen::VectorXd& external_new,
                            Eigen::VectorXd& internal, Eigen::VectorXd& inertia, AssembleNewLevel&& assemble,
                            Eigen::VectorXd& residual) const {
    const double old_weight = old_force_weight(), inertia_weight = old_inertia_weight();
    if (old_weight == 0.0 && inertia_weight == 0.0) return;
    if (old_weight != 0.0) residual -= old_weight * (internal - external_old);
    if (inertia_weight != 0.0) residual -= inertia_weight * inertia;
    assemble(internal, inertia);
    if (old_weight != 0.0) residual += old_weight * (internal - external_new);
    if (inertia_weight != 0.0) residual += inertia_weight * inertia;
  }

  /// Predicts the state at t_n + step from the committed state (every DOF).
  void predict(const State& committed, double step, State& trial) const {
    scheme_->predict(committed, step, predictor_, trial);
  }
  /// Velocity and acceleration of one DOF whose displacement is known at t_{n+1}
  /// (a prescribed DOF, or a free DOF after a Newton correction).
  void update_rates(const State& committed, double step, int dof, State& trial) const {
    scheme_->update_rates(committed, step, dof, trial);
  }
  /// The rate changes of Newton increments over a step of size 'step' (one virtual call
  /// per iteration, then inline per DOF).
  RateCorrection rate_correction(double step) const { return scheme_->rate_correction(step); }
  /// Adds a Newton increment du to a free DOF with its consistent rate changes.
  void correct(double step, int dof, double increment, State& trial) const {
    rate_correction(step).apply(dof, increment, trial);
  }

 private:
  std::shared_ptr<const TimeScheme> scheme_;
  Predictor predictor_ = Predictor::SameAcceleration;
};

/// The deck's integrators by name (model:integrator{ type = ... }, a vehicle's tires, the
/// C API): "static" and the generalized-alpha presets, made from the parameters given.
struct IntegratorParameters {
  double beta = 0.25, gamma = 0.5, alpha = -0.05, rho_inf = 0.9;
  Integrator::Predictor predictor = Integrator::Predictor::SameAcceleration;
};
/// A preset: its name, its checkpoint number (never reused) and its four numbers.
struct AlphaPreset {
  const char* name;
  int kind;
  AlphaParameters (*parameters)(const IntegratorParameters& given);
};
const std::vector<AlphaPreset>& alpha_presets();
/// "static" and the presets' names.
std::vector<std::string> integrator_names();
/// ModelError naming the known schemes for an unknown name.
Integrator make_integrator(const std::string& name, const IntegratorParameters& parameters);
/// The predictors' deck names, in Predictor's order.
std::vector<std::string> predictor_names();
Integrator::Predictor predictor_named(const std::string& name);

}  // namespace tirefe
