#include "solvers/integrators/newmark.hpp"

#include <sstream>

#include "core/mesh.hpp"

namespace tirefe {

// Unconditional stability of Newmark's family on linear systems: 1/2 <= gamma and
// gamma/2 <= beta (Hughes 2000, 9.1). Below gamma/2 the scheme is stable only for
// omega h < 1/sqrt(gamma/2 - beta), which a tire's unresolved stiff modes never meet, and
// beta -> 0 sends the tangent factor 1/(beta h^2) to overflow. gamma > 1 and beta > 1 are
// refused as input slips: they only add damping and period error.
std::shared_ptr<const Newmark> Newmark::make(double beta, double gamma) {
  if (!(gamma >= 0.5 && gamma <= 1.0) || !(beta >= 0.5 * gamma && beta <= 1.0)) {
    std::ostringstream message;
    message << "Newmark needs 1/2 <= gamma <= 1 and gamma/2 <= beta <= 1 (unconditionally stable; "
               "average acceleration: beta = 1/4, gamma = 1/2); got beta = "
            << beta << ", gamma = " << gamma;
    throw ModelError(message.str());
  }
  return std::shared_ptr<const Newmark>(new Newmark(beta, gamma));
}

std::string Newmark::name() const {
  std::ostringstream text;
  text << "Newmark(beta=" << beta_ << ", gamma=" << gamma_ << ")";
  return text.str();
}

std::optional<double> Newmark::hht_alpha() const {
  if (beta_ == 0.25 && gamma_ == 0.5) return 0.0;  // average acceleration
  return std::nullopt;
}

IntegratorFactors Newmark::factors(double step) const {
  const double weight = new_force_weight();
  IntegratorFactors factors;
  factors.force_stiffness = weight;
  factors.force_damping = weight;
  factors.force_mass = 1.0;
  factors.tangent_stiffness = weight;
  factors.tangent_damping = weight * gamma_ / (beta_ * step);
  factors.tangent_mass = 1.0 / (beta_ * step * step);
  return factors;
}

IntegratorFactors Newmark::physical_residual_factors() const {
  IntegratorFactors factors;
  factors.force_stiffness = 1.0;
  factors.force_damping = 1.0;
  factors.force_mass = 1.0;
  factors.tangent_stiffness = 0.0;
  return factors;
}

void Newmark::predict(const State& committed, double step, Predictor predictor, State& trial) const {
  trial.time = committed.time + step;
  if (predictor == Predictor::SameAcceleration) {  // the Newmark formulas below with a_{n+1} = a_n, summed exactly
    trial.acceleration = committed.acceleration;
    trial.velocity = committed.velocity + step * committed.acceleration;
    trial.displacement =
        committed.displacement + step * committed.velocity + (0.5 * step * step) * committed.acceleration;
    return;
  }
  if (predictor == Predictor::ZeroAcceleration)
    trial.acceleration.setZero(committed.acceleration.size());
  else  // SameDisplacement: the acceleration that keeps u_{n+1} = u_n
    trial.acceleration =
        (-1.0 / (beta_ * step)) * committed.velocity - ((0.5 - beta_) / beta_) * committed.acceleration;
  // The Newmark formulas with the predicted a_{n+1}.
  trial.velocity = committed.velocity + step * ((1.0 - gamma_) * committed.acceleration + gamma_ * trial.acceleration);
  trial.displacement = committed.displacement + step * committed.velocity +
                       (step * step) * ((0.5 - beta_) * committed.acceleration + beta_ * trial.acceleration);
}

void Newmark::update_rates(const State& committed, double step, int dof, State& trial) const {
  const double a_old = committed.acceleration[dof];
  const double a_new = (trial.displacement[dof] - committed.displacement[dof] - step * committed.velocity[dof] -
                        step * step * (0.5 - beta_) * a_old) /
                       (beta_ * step * step);
  trial.acceleration[dof] = a_new;
  trial.velocity[dof] = committed.velocity[dof] + step * ((1.0 - gamma_) * a_old + gamma_ * a_new);
}

// The end-of-step velocity fixes the acceleration, which fixes the displacement.
double Newmark::displacement_for_velocity(double u, double v, double a, double new_velocity, double step) const {
  const double h = step;
  const double a_new = (new_velocity - v - h * (1.0 - gamma_) * a) / (gamma_ * h);
  return u + h * v + h * h * ((0.5 - beta_) * a + beta_ * a_new);
}

}  // namespace tirefe
