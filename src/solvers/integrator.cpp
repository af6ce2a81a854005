#include "solvers/integrator.hpp"

#include "core/mesh.hpp"
#include "solvers/integrators/hht.hpp"
#include "solvers/integrators/newmark.hpp"
#include "solvers/integrators/quasi_static.hpp"

namespace tirefe {

Integrator Integrator::quasi_static() {
  static const auto scheme = std::make_shared<const QuasiStatic>();  // one for every analysis: no state
  return Integrator(scheme);
}

Integrator Integrator::newmark(double beta, double gamma) { return Integrator(Newmark::make(beta, gamma)); }

Integrator Integrator::hht(double alpha) { return Integrator(Hht::make(alpha)); }

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

// A new scheme: its file pair in integrators/ and one line here.
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
