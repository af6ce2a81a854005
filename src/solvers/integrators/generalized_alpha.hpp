// GeneralizedAlpha(alpha_m, alpha_f, beta, gamma): the family of time_scheme.hpp's
// convention (Chung & Hulbert 1993). Newmark, HHT-alpha, WBZ-alpha and Chung-Hulbert's
// optimal member are its presets: AlphaParameters' functions, named in integrator.cpp.
#pragma once

#include <memory>

#include "solvers/integrators/time_scheme.hpp"

namespace tirefe {

/// The four numbers of a member of the family.
struct AlphaParameters {
  double alpha_m = 0.0, alpha_f = 0.0, beta = 0.25, gamma = 0.5;

  /// Newmark(beta, gamma): 1/2 <= gamma <= 1, gamma/2 <= beta <= 1 (unconditionally stable);
  /// ModelError with the ranges otherwise.
  static AlphaParameters newmark(double beta, double gamma);
  /// HHT-alpha, alpha in [-1/3, 0]: alpha_m = 0, alpha_f = -alpha (ModelError otherwise).
  static AlphaParameters hht(double alpha);
  /// WBZ-alpha (Wood, Bossak, Zienkiewicz 1980): alpha_f = 0, alpha_m = (rho - 1)/(rho + 1).
  static AlphaParameters wbz(double rho_inf);
  /// Chung-Hulbert: alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1).
  static AlphaParameters chung_hulbert(double rho_inf);
  /// The second-order member with these weights: gamma = 1/2 - alpha_m + alpha_f and
  /// beta = (1 - alpha_m + alpha_f)^2 / 4, which damps the high frequencies most.
  static AlphaParameters second_order(double alpha_m, double alpha_f);
};

class GeneralizedAlpha final : public TimeScheme {
 public:
  /// A preset's scheme: 'kind' its checkpoint number, 'label' its name in messages.
  /// ModelError unless alpha_m <= alpha_f <= 1/2 (unconditional stability).
  static std::shared_ptr<const GeneralizedAlpha> make(int kind, const char* label, const AlphaParameters& parameters);

  const AlphaParameters& parameters() const { return parameters_; }
  double beta() const { return parameters_.beta; }
  double gamma() const { return parameters_.gamma; }

  std::string name() const override;
  bool is_dynamic() const override { return true; }
  SchemeRecord record() const override {
    return {kind_, parameters_.beta, parameters_.gamma, -parameters_.alpha_f, parameters_.alpha_m};
  }
  std::optional<double> hht_alpha() const override;
  double new_force_weight() const override { return 1.0 - parameters_.alpha_f; }
  double old_force_weight() const override { return parameters_.alpha_f; }
  double old_inertia_weight() const override { return parameters_.alpha_m; }
  IntegratorFactors factors(double step) const override;
  IntegratorFactors physical_residual_factors() const override {
    return {1.0, 1.0, 1.0, 0.0, 0.0, 0.0};  // M a + C v + f_int, no tangent
  }
  void predict(const State& committed, double step, Predictor predictor, State& trial) const override;
  void update_rates(const State& committed, double step, int dof, State& trial) const override;
  RateCorrection rate_correction(double step) const override {
    return {true, gamma() / (beta() * step), beta() * step * step};
  }
  double displacement_for_velocity(double u, double v, double a, double new_velocity, double step) const override;
  double displacement_per_velocity(double step) const override { return beta() * step / gamma(); }

  /// The checkpoint numbers of the presets that have their own (0 is quasi-static).
  static constexpr int kNewmarkKind = 1, kHhtKind = 2;

 private:
  GeneralizedAlpha(int kind, const char* label, const AlphaParameters& parameters)
      : kind_(kind), label_(label), parameters_(parameters) {}

  int kind_;
  const char* label_;
  AlphaParameters parameters_;
};

}  // namespace tirefe
