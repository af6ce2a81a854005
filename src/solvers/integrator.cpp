#include "solvers/integrator.hpp"

#include "core/mesh.hpp"
#include "solvers/integrators/quasi_static.hpp"

namespace tirefe {

Integrator Integrator::quasi_static() {
  static const auto scheme = std::make_shared<const QuasiStatic>();  // one for every analysis: no state
  return Integrator(scheme);
}

Integrator Integrator::newmark(double beta, double gamma) {
  IntegratorParameters given;
  given.beta = beta;
  given.gamma = gamma;
  return make_integrator("newmark", given);
}

Integrator Integrator::hht(double alpha) {
  IntegratorParameters given;
  given.alpha = alpha;
  return make_integrator("hht", given);
}

Integrator Integrator::generalized_alpha(double rho_inf) {
  IntegratorParameters given;
  given.rho_inf = rho_inf;
  return make_integrator("generalized_alpha", given);
}

IntegratorFactors Integrator::internal_force_factors() {
  IntegratorFactors factors;
  factors.force_stiffness = 1.0;
  factors.force_damping = 1.0;
  factors.tangent_stiffness = 0.0;
  return factors;
}

IntegratorFactors Integrator::initial_acceleration_factors() {
  IntegratorFactors factors = internal_force_factors();
  factors.tangent_mass = 1.0;
  return factors;
}

// A new member of the family: one line here, a name, a checkpoint number not used before
// and its four numbers from the deck's parameters (docs/dynamics.md, Adding a scheme).
const std::vector<AlphaPreset>& alpha_presets() {
  using P = IntegratorParameters;
  static const std::vector<AlphaPreset> presets = {
      {"newmark", GeneralizedAlpha::kNewmarkKind, [](const P& p) { return AlphaParameters::newmark(p.beta, p.gamma); }},
      {"hht", GeneralizedAlpha::kHhtKind, [](const P& p) { return AlphaParameters::hht(p.alpha); }},
      {"wbz", 3, [](const P& p) { return AlphaParameters::wbz(p.rho_inf); }},
      {"generalized_alpha", 4, [](const P& p) { return AlphaParameters::chung_hulbert(p.rho_inf); }},
  };
  return presets;
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names{"static"};
  for (const AlphaPreset& preset : alpha_presets()) names.emplace_back(preset.name);
  return names;
}

Integrator make_integrator(const std::string& name, const IntegratorParameters& parameters) {
  if (name == "static") return Integrator::quasi_static();
  for (const AlphaPreset& preset : alpha_presets())
    if (name == preset.name)
      return Integrator(GeneralizedAlpha::make(preset.kind, preset.name, preset.parameters(parameters)))
          .with_predictor(parameters.predictor);
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
