#include "solvers/integrators/generalized_alpha.hpp"

#include <sstream>

#include "core/mesh.hpp"

namespace tirefe {

// Unconditional stability of Newmark's family on linear systems: 1/2 <= gamma and
// gamma/2 <= beta (Hughes 2000, 9.1). Below gamma/2 the scheme is stable only for
// omega h < 1/sqrt(gamma/2 - beta), which a tire's unresolved stiff modes never meet, and
// beta -> 0 sends the tangent factor 1/(beta h^2) to overflow. gamma > 1 and beta > 1 are
// refused as input slips: they only add damping and period error.
AlphaParameters AlphaParameters::newmark(double beta, double gamma) {
  if (!(gamma >= 0.5 && gamma <= 1.0) || !(beta >= 0.5 * gamma && beta <= 1.0)) {
    std::ostringstream message;
    message << "Newmark needs 1/2 <= gamma <= 1 and gamma/2 <= beta <= 1 (unconditionally stable; "
               "average acceleration: beta = 1/4, gamma = 1/2); got beta = "
            << beta << ", gamma = " << gamma;
    throw ModelError(message.str());
  }
  return {0.0, 0.0, beta, gamma};
}

AlphaParameters AlphaParameters::hht(double alpha) {
  if (!(alpha >= -1.0 / 3.0 && alpha <= 0.0)) {
    std::ostringstream message;
    message << "HHT needs alpha in [-1/3, 0] (unconditionally stable and second-order accurate); got " << alpha;
    throw ModelError(message.str());
  }
  return second_order(0.0, -alpha);
}

namespace {
void check_rho_inf(double rho_inf, const char* scheme) {
  if (rho_inf >= 0.0 && rho_inf <= 1.0) return;
  std::ostringstream message;
  message << scheme << " needs rho_inf in [0, 1] (the spectral radius at omega h -> infinity: 1 keeps every "
          << "frequency, 0 annihilates the highest in one step); got " << rho_inf;
  throw ModelError(message.str());
}
}  // namespace

AlphaParameters AlphaParameters::wbz(double rho_inf) {
  check_rho_inf(rho_inf, "WBZ-alpha");
  return second_order((rho_inf - 1.0) / (rho_inf + 1.0), 0.0);
}

AlphaParameters AlphaParameters::chung_hulbert(double rho_inf) {
  check_rho_inf(rho_inf, "generalized-alpha");
  return second_order((2.0 * rho_inf - 1.0) / (rho_inf + 1.0), rho_inf / (rho_inf + 1.0));
}

AlphaParameters AlphaParameters::second_order(double alpha_m, double alpha_f) {
  const double shift = 1.0 - alpha_m + alpha_f;
  return {alpha_m, alpha_f, 0.25 * shift * shift, 0.5 - alpha_m + alpha_f};
}

// Chung & Hulbert (1993): alpha_m <= alpha_f <= 1/2 with the beta and gamma a preset gives
// (its own checks) keeps every member unconditionally stable on linear systems.
std::shared_ptr<const GeneralizedAlpha> GeneralizedAlpha::make(int kind, const char* label,
                                                               const AlphaParameters& parameters) {
  if (!(parameters.alpha_m <= parameters.alpha_f && parameters.alpha_f <= 0.5)) {
    std::ostringstream message;
    message << label
            << " needs alpha_m <= alpha_f <= 1/2 (unconditionally stable); got alpha_m = " << parameters.alpha_m
            << ", alpha_f = " << parameters.alpha_f;
    throw ModelError(message.str());
  }
  return std::shared_ptr<const GeneralizedAlpha>(new GeneralizedAlpha(kind, label, parameters));
}

std::string GeneralizedAlpha::name() const {
  std::ostringstream text;
  text << label_ << "(alpha_m=" << parameters_.alpha_m << ", alpha_f=" << parameters_.alpha_f
       << ", beta=" << parameters_.beta << ", gamma=" << parameters_.gamma << ")";
  return text.str();
}

std::optional<double> GeneralizedAlpha::hht_alpha() const {
  if (kind_ == kHhtKind) return -parameters_.alpha_f;
  if (kind_ == kNewmarkKind && beta() == 0.25 && gamma() == 0.5) return 0.0;  // average acceleration
  return std::nullopt;
}

IntegratorFactors GeneralizedAlpha::factors(double step) const {
  const double weight = new_force_weight(), inertia_weight = 1.0 - parameters_.alpha_m;
  IntegratorFactors factors;
  factors.force_stiffness = weight;
  factors.force_damping = weight;
  factors.force_mass = inertia_weight;
  factors.tangent_stiffness = weight;
  factors.tangent_damping = weight * gamma() / (beta() * step);
  factors.tangent_mass = inertia_weight / (beta() * step * step);
  return factors;
}

void GeneralizedAlpha::predict(const State& committed, double step, Predictor predictor, State& trial) const {
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
        (-1.0 / (beta() * step)) * committed.velocity - ((0.5 - beta()) / beta()) * committed.acceleration;
  // The Newmark formulas with the predicted a_{n+1}.
  trial.velocity =
      committed.velocity + step * ((1.0 - gamma()) * committed.acceleration + gamma() * trial.acceleration);
  trial.displacement = committed.displacement + step * committed.velocity +
                       (step * step) * ((0.5 - beta()) * committed.acceleration + beta() * trial.acceleration);
}

void GeneralizedAlpha::update_rates(const State& committed, double step, int dof, State& trial) const {
  const double a_old = committed.acceleration[dof];
  const double a_new = (trial.displacement[dof] - committed.displacement[dof] - step * committed.velocity[dof] -
                        step * step * (0.5 - beta()) * a_old) /
                       (beta() * step * step);
  trial.acceleration[dof] = a_new;
  trial.velocity[dof] = committed.velocity[dof] + step * ((1.0 - gamma()) * a_old + gamma() * a_new);
}

// The end-of-step velocity fixes the acceleration, which fixes the displacement.
double GeneralizedAlpha::displacement_for_velocity(double u, double v, double a, double new_velocity,
                                                   double step) const {
  const double h = step;
  const double a_new = (new_velocity - v - h * (1.0 - gamma()) * a) / (gamma() * h);
  return u + h * v + h * h * ((0.5 - beta()) * a + beta() * a_new);
}

}  // namespace tirefe
