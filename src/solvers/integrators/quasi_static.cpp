#include "solvers/integrators/quasi_static.hpp"

#include "core/mesh.hpp"

namespace tirefe {

IntegratorFactors QuasiStatic::physical_residual_factors() const {
  IntegratorFactors factors;
  factors.force_stiffness = 1.0;
  factors.force_damping = 0.0;
  factors.force_mass = 0.0;
  factors.tangent_stiffness = 0.0;
  return factors;
}

void QuasiStatic::predict(const State& committed, double step, Predictor, State& trial) const {
  trial.time = committed.time + step;
  trial.displacement = committed.displacement;
  trial.velocity.setZero();
  trial.acceleration.setZero();
}

double QuasiStatic::displacement_for_velocity(double, double, double, double, double) const {
  throw ModelError("a quasi-static analysis has no velocities to drive");
}

double QuasiStatic::displacement_per_velocity(double) const {
  throw ModelError("a quasi-static analysis has no velocities to drive");
}

}  // namespace tirefe
