// QuasiStatic: load levels instead of time; no inertia, no damping, no rates.
#pragma once

#include "solvers/integrators/time_scheme.hpp"

namespace tirefe {

class QuasiStatic final : public TimeScheme {
 public:
  static constexpr int kRecordKind = 0;

  std::string name() const override { return "quasi-static"; }
  bool is_dynamic() const override { return false; }
  SchemeRecord record() const override { return {kRecordKind, 0.25, 0.5, 0.0}; }
  std::optional<double> hht_alpha() const override { return std::nullopt; }
  IntegratorFactors factors(double) const override { return {}; }  // f_int and K alone
  IntegratorFactors physical_residual_factors() const override;
  void predict(const State& committed, double step, Predictor predictor, State& trial) const override;
  void update_rates(const State&, double, int, State&) const override {}
  RateCorrection rate_correction(double) const override { return {}; }
  double displacement_for_velocity(double, double, double, double, double) const override;
  double displacement_per_velocity(double) const override;
};

}  // namespace tirefe
