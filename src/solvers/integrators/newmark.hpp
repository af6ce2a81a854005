// Newmark(beta, gamma): M a_{n+1} + g_{n+1} = F_{n+1} with the Newmark formulas for
// u_{n+1} and v_{n+1} (time_scheme.hpp). Unconditionally stable on linear systems for
// 1/2 <= gamma and gamma/2 <= beta; average acceleration (1/4, 1/2) by default.
#pragma once

#include <memory>

#include "solvers/integrators/time_scheme.hpp"

namespace tirefe {

class Newmark : public TimeScheme {
 public:
  static constexpr int kRecordKind = 1;

  /// 1/2 <= gamma <= 1, gamma/2 <= beta <= 1; ModelError with the ranges otherwise.
  static std::shared_ptr<const Newmark> make(double beta = 0.25, double gamma = 0.5);

  double beta() const { return beta_; }
  double gamma() const { return gamma_; }

  std::string name() const override;
  bool is_dynamic() const override { return true; }
  SchemeRecord record() const override { return {kRecordKind, beta_, gamma_, 0.0}; }
  std::optional<double> hht_alpha() const override;
  IntegratorFactors factors(double step) const override;
  IntegratorFactors physical_residual_factors() const override;
  void predict(const State& committed, double step, Predictor predictor, State& trial) const override;
  void update_rates(const State& committed, double step, int dof, State& trial) const override;
  RateCorrection rate_correction(double step) const override {
    return {true, gamma_ / (beta_ * step), beta_ * step * step};
  }
  double displacement_for_velocity(double u, double v, double a, double new_velocity, double step) const override;
  double displacement_per_velocity(double step) const override { return beta_ * step / gamma_; }

 protected:
  Newmark(double beta, double gamma) : beta_(beta), gamma_(gamma) {}

 private:
  double beta_, gamma_;
};

}  // namespace tirefe
