#include "solvers/integrator.hpp"

#include <sstream>

#include "core/mesh.hpp"

namespace tirefe {

namespace {

std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

}  // namespace

// Unconditional stability of Newmark's family on linear systems: 1/2 <= gamma and
// gamma/2 <= beta (Hughes 2000, 9.1). Below gamma/2 the scheme is stable only for
// omega h < 1/sqrt(gamma/2 - beta), which a tire's unresolved stiff modes never meet, and
// beta -> 0 sends the tangent factor 1/(beta h^2) to overflow. gamma > 1 and beta > 1 are
// refused as input slips: they only add damping and period error.
Integrator Integrator::newmark(double beta, double gamma) {
  if (!(gamma >= 0.5 && gamma <= 1.0) || !(beta >= 0.5 * gamma && beta <= 1.0))
    throw ModelError(
        "Newmark needs 1/2 <= gamma <= 1 and gamma/2 <= beta <= 1 (unconditionally stable; "
        "average acceleration: beta = 1/4, gamma = 1/2); got beta = " +
        number_text(beta) + ", gamma = " + number_text(gamma));
  return Integrator(Kind::Newmark, beta, gamma, 0.0);
}

Integrator Integrator::hht(double alpha) {
  if (!(alpha >= -1.0 / 3.0 && alpha <= 0.0))
    throw ModelError("HHT needs alpha in [-1/3, 0] (unconditionally stable and second-order accurate); got " +
                     number_text(alpha));
  return Integrator(Kind::Hht, 0.25 * (1.0 - alpha) * (1.0 - alpha), 0.5 - alpha, alpha);
}

std::string Integrator::name() const {
  std::ostringstream text;
  switch (kind_) {
    case Kind::QuasiStatic: return "quasi-static";
    case Kind::Newmark: text << "Newmark(beta=" << beta_ << ", gamma=" << gamma_ << ")"; break;
    case Kind::Hht: text << "HHT(alpha=" << alpha_ << ")"; break;
  }
  return text.str();
}

IntegratorFactors Integrator::factors(double step) const {
  if (!is_dynamic()) return {};  // f_int and K alone
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

IntegratorFactors Integrator::internal_force_factors() {
  IntegratorFactors factors;
  factors.force_stiffness = 1.0;
  factors.force_damping = 1.0;
  factors.tangent_stiffness = 0.0;
  return factors;
}

IntegratorFactors Integrator::physical_residual_factors() const {
  IntegratorFactors factors;
  factors.force_stiffness = 1.0;
  factors.force_damping = is_dynamic() ? 1.0 : 0.0;
  factors.force_mass = is_dynamic() ? 1.0 : 0.0;
  factors.tangent_stiffness = 0.0;
  return factors;
}

IntegratorFactors Integrator::initial_acceleration_factors() {
  IntegratorFactors factors = internal_force_factors();
  factors.tangent_mass = 1.0;
  return factors;
}

void Integrator::predict(const State& committed, double step, State& trial) const {
  trial.time = committed.time + step;
  if (!is_dynamic()) {
    trial.displacement = committed.displacement;
    trial.velocity.setZero();
    trial.acceleration.setZero();
    return;
  }
  if (predictor_ == Predictor::SameAcceleration) {  // the Newmark formulas below with a_{n+1} = a_n, summed exactly
    trial.acceleration = committed.acceleration;
    trial.velocity = committed.velocity + step * committed.acceleration;
    trial.displacement =
        committed.displacement + step * committed.velocity + (0.5 * step * step) * committed.acceleration;
    return;
  }
  if (predictor_ == Predictor::ZeroAcceleration)
    trial.acceleration.setZero(committed.acceleration.size());
  else  // SameDisplacement: the acceleration that keeps u_{n+1} = u_n
    trial.acceleration =
        (-1.0 / (beta_ * step)) * committed.velocity - ((0.5 - beta_) / beta_) * committed.acceleration;
  // The Newmark formulas with the predicted a_{n+1}.
  trial.velocity = committed.velocity + step * ((1.0 - gamma_) * committed.acceleration + gamma_ * trial.acceleration);
  trial.displacement = committed.displacement + step * committed.velocity +
                       (step * step) * ((0.5 - beta_) * committed.acceleration + beta_ * trial.acceleration);
}

void Integrator::update_rates(const State& committed, double step, int dof, State& trial) const {
  if (!is_dynamic()) return;
  const double a_old = committed.acceleration[dof];
  const double a_new = (trial.displacement[dof] - committed.displacement[dof] - step * committed.velocity[dof] -
                        step * step * (0.5 - beta_) * a_old) /
                       (beta_ * step * step);
  trial.acceleration[dof] = a_new;
  trial.velocity[dof] = committed.velocity[dof] + step * ((1.0 - gamma_) * a_old + gamma_ * a_new);
}

const std::vector<IntegratorScheme>& integrator_schemes() {
  static const std::vector<IntegratorScheme> schemes = {
      {"static", [](const IntegratorParameters&) { return Integrator::quasi_static(); }},
      {"newmark",
       [](const IntegratorParameters& p) { return Integrator::newmark(p.beta, p.gamma).with_predictor(p.predictor); }},
      {"hht", [](const IntegratorParameters& p) { return Integrator::hht(p.alpha).with_predictor(p.predictor); }},
  };
  return schemes;
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const IntegratorScheme& scheme : integrator_schemes()) names.emplace_back(scheme.name);
  return names;
}

Integrator make_integrator(const std::string& name, const IntegratorParameters& parameters) {
  for (const IntegratorScheme& scheme : integrator_schemes())
    if (name == scheme.name) return scheme.make(parameters);
  std::string known;
  for (const std::string& other : integrator_names()) known += (known.empty() ? "" : ", ") + other;
  throw ModelError("no integrator named '" + name + "' (known: " + known + ")");
}

std::vector<std::string> predictor_names() { return {"same_acceleration", "zero_acceleration", "same_displacement"}; }

Integrator::Predictor predictor_named(const std::string& name) {
  const std::vector<std::string> names = predictor_names();
  for (size_t i = 0; i < names.size(); ++i)
    if (name == names[i]) return static_cast<Integrator::Predictor>(i);
  throw ModelError("no predictor named '" + name + "'");
}

}  // namespace tirefe
