#include "elements/tread_pressure.hpp"

#include <cmath>
#include <string>

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
  const Vector& u = local.displacement;
  const IntegratorFactors& f = context.factors;
  const double half_load = 0.5 * pressure_->at(context.time) * width_;  // p w / 2
  const Eigen::Vector2d chord = reference_chord_ + u.segment<2>(3) - u.segment<2>(0);
  const Eigen::Vector2d inward_normal(-chord.y(), chord.x());  // k x c, length |c|

  residual.setZero();
  residual.segment<2>(0) = residual.segment<2>(3) = (f.force_stiffness * half_load) * inward_normal;
  if (!tangent) return;

  Matrix& K = *tangent;
  K.setZero();
  const double entry = f.tangent_stiffness * half_load;
  for (int row : {0, 3}) {
    // d(k x c)/du_b = [k x] = [[0, -1], [1, 0]], d(k x c)/du_a = -[k x].
    K(row, 1) = entry;
    K(row + 1, 0) = -entry;
    K(row, 4) = -entry;
    K(row + 1, 3) = entry;
  }
}

ElementEnergy TreadPressure::energy(const LocalState<kDofs>&, const History&) const { return {}; }

}  // namespace tirefe
