// HHT-alpha (Hilber, Hughes & Taylor 1977): Newmark with beta = (1-alpha)^2/4,
// gamma = (1-2 alpha)/2 whose internal and external forces are weighted 1+alpha at
// t_{n+1} and -alpha at t_n: numerical damping of the high modes, second order.
#pragma once

#include "solvers/integrators/newmark.hpp"

namespace tirefe {

class Hht final : public Newmark {
 public:
  static constexpr int kRecordKind = 2;

  /// alpha in [-1/3, 0] (ModelError with the range otherwise).
  static std::shared_ptr<const Hht> make(double alpha);

  double alpha() const { return alpha_; }

  std::string name() const override;
  SchemeRecord record() const override { return {kRecordKind, beta(), gamma(), alpha_}; }
  std::optional<double> hht_alpha() const override { return alpha_; }
  double new_force_weight() const override { return 1.0 + alpha_; }
  double old_force_weight() const override { return -alpha_; }

 private:
  explicit Hht(double alpha) : Newmark(0.25 * (1.0 - alpha) * (1.0 - alpha), 0.5 - alpha), alpha_(alpha) {}

  double alpha_;
};

}  // namespace tirefe
