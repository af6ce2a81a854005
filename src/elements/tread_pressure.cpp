#include "elements/tread_pressure.hpp"

#include <cmath>
#include <string>

#include "core/batch_of_one.hpp"

namespace tirefe {

TreadPressure::TreadPressure(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double width,
                             std::shared_ptr<const PressureSchedule> pressure)
    : reference_chord_(end - start), width_(width), pressure_(std::move(pressure)) {
  if (!std::isfinite(width) || !(width > 0.0))
    throw ModelError("tread pressure: the tread width must be positive (got " + std::to_string(width) + ")");
  if (!pressure_) throw ModelError("tread pressure: a pressure schedule is required");
  if (!(reference_chord_.norm() > 0.0)) throw ModelError("tread pressure: the two tread nodes coincide");
}

void TreadPressure::evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&, History&,
                             Vector& residual, Matrix* tangent) const {
  evaluate_as_batch(*this, local, context, residual, tangent);
}

ElementEnergy TreadPressure::energy(const LocalState<kDofs>&, const History&) const { return {}; }

TreadPressure::Batch::Batch(const std::vector<TreadPressure>& loads) { assign(loads); }

void TreadPressure::Batch::assign(const std::vector<TreadPressure>& loads) {
  loads_ = loads;
  const size_t n = loads_.size();
  chord_x_.resize(n);
  chord_y_.resize(n);
  half_load_.resize(n);
  // The entries the passes never write (idle DOFs') stay zero: cleared for a new layout alone,
  // so that a batch given other elements of the same number allocates and clears nothing.
  if (residual_.size() != kDofs * n) {
    residual_.assign(kDofs * n, 0.0);
    tangent_.assign(kDofs * kDofs * n, 0.0);
  }
  for (size_t e = 0; e < n; ++e) {
    chord_x_[e] = loads_[e].reference_chord_.x();
    chord_y_[e] = loads_[e].reference_chord_.y();
  }
}

void TreadPressure::Batch::evaluate(const BlockValues& values, const EvaluationContext& context, bool with_tangent) {
  const int n = size();
  // Every load of a tire reads one schedule: its pressure is looked up once.
  const PressureSchedule* schedule = nullptr;
  double pressure = 0.0;
  for (int e = 0; e < n; ++e) {
    const TreadPressure& load = loads_[e];
    if (load.pressure_.get() != schedule) {
      schedule = load.pressure_.get();
      pressure = schedule->at(context.time);
    }
    half_load_[e] = 0.5 * pressure * load.width_;
  }
  const IntegratorFactors& f = context.factors;
  const double* u = values.displacement;
  double* residual = residual_.data();
  double* tangent = tangent_.data();
#pragma omp simd
  for (int e = 0; e < n; ++e) {
    // r_a = r_b = (p w / 2) k x c, c the deformed chord.
    const double chord_x = chord_x_[e] + u[3 * n + e] - u[e], chord_y = chord_y_[e] + u[4 * n + e] - u[n + e];
    const double load = f.force_stiffness * half_load_[e];
    residual[e] = residual[3 * n + e] = load * -chord_y;
    residual[n + e] = residual[4 * n + e] = load * chord_x;
  }
  if (!with_tangent) return;
    // d(k x c)/du_b = [k x] = [[0, -1], [1, 0]], d(k x c)/du_a = -[k x].
#pragma omp simd
  for (int e = 0; e < n; ++e) {
    const double entry = f.tangent_stiffness * half_load_[e];
    for (int row = 0; row < kDofs; row += 3) {
      tangent[(row * kDofs + 1) * n + e] = entry;
      tangent[((row + 1) * kDofs) * n + e] = -entry;
      tangent[(row * kDofs + 4) * n + e] = -entry;
      tangent[((row + 1) * kDofs + 3) * n + e] = entry;
    }
  }
}

}  // namespace tirefe
