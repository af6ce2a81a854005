#include "elements/point_mass.hpp"

#include <cmath>
#include <string>

namespace tirefe {

void SpringMassProperties::check() const {
  auto require_nonnegative = [](double value, const std::string& name) {
    if (!std::isfinite(value) || value < 0.0)
      throw ModelError("spring-mass: " + name + " must be a non-negative finite number (got " + std::to_string(value) +
                       ")");
  };
  const char* components[3] = {"x", "y", "rz"};
  for (int c = 0; c < 3; ++c) {
    require_nonnegative(stiffness[c], std::string("stiffness k_") + components[c]);
    require_nonnegative(damping[c], std::string("damping c_") + components[c]);
  }
  require_nonnegative(mass, "mass");
  require_nonnegative(rotary_inertia, "rotary inertia");
}

NodalSpringMass::NodalSpringMass(const SpringMassProperties& properties)
    : properties_(properties), inertia_(properties.inertia()) {
  properties_.check();
}

void NodalSpringMass::evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&,
                               History&, Vector& residual, Matrix* tangent) const {
  const IntegratorFactors& f = context.factors;
  residual = f.force_stiffness * properties_.stiffness.cwiseProduct(local.displacement) +
             f.force_damping * properties_.damping.cwiseProduct(local.velocity) +
             f.force_mass * inertia_.cwiseProduct(local.acceleration);
  if (!tangent) return;
  tangent->setZero();
  tangent->diagonal() =
      f.tangent_stiffness * properties_.stiffness + f.tangent_damping * properties_.damping + f.tangent_mass * inertia_;
}

ElementEnergy NodalSpringMass::energy(const LocalState<kDofs>& local, const History&) const {
  ElementEnergy energy;
  energy.strain = 0.5 * local.displacement.dot(properties_.stiffness.cwiseProduct(local.displacement));
  energy.kinetic = 0.5 * local.velocity.dot(inertia_.cwiseProduct(local.velocity));
  return energy;
}

}  // namespace tirefe
