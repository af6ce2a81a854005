// The generalized-alpha presets (Newmark, HHT, WBZ, Chung-Hulbert) against closed forms:
// their four numbers from rho_inf or alpha, the characteristic polynomial of the
// single-DOF oscillator (Chung & Hulbert 1993), its spectral radius at omega h -> infinity
// and at 0.1, 1, 10 and the leading term of the period error; each against an
// amplification matrix built here from the convention and against runs of the
// integrator itself. Also the registry's names, a checkpoint's round trip, the deck and
// docs/dynamics.md's example of a new preset.
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "deck_support.hpp"
#include "elements/point_mass.hpp"
#include "deck/checkpoint.hpp"
#include "solvers/analysis.hpp"
#include "test_support.hpp"

using namespace tirefe;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A member of the family as the literature gives it: the four numbers, and the spectral
/// radius at omega h -> infinity.
struct Member {
  std::string label;
  Integrator integrator;
  double alpha_m, alpha_f, beta, gamma, rho_inf;
};

/// Second-order accuracy fixes gamma = 1/2 - alpha_m + alpha_f, and beta = (1 - alpha_m +
/// alpha_f)^2 / 4 makes the high-frequency roots meet (Chung & Hulbert 1993, eq. 25).
Member second_order_member(std::string label, Integrator integrator, double alpha_m, double alpha_f, double rho_inf) {
  const double shift = 1.0 - alpha_m + alpha_f;
  return {std::move(label),    std::move(integrator),   alpha_m, alpha_f,
          shift * shift / 4.0, 0.5 - alpha_m + alpha_f, rho_inf};
}

std::vector<Member> members() {
  std::vector<Member> list;
  // Newmark average acceleration keeps every amplitude; with gamma > 1/2 and
  // beta = (gamma + 1/2)^2 / 4 its limit roots are a double root (gamma - 3/2)/(gamma + 1/2).
  list.push_back({"newmark(1/4, 1/2)", Integrator::newmark(), 0.0, 0.0, 0.25, 0.5, 1.0});
  list.push_back({"newmark(0.36, 0.7)", Integrator::newmark(0.36, 0.7), 0.0, 0.0, 0.36, 0.7, 0.8 / 1.2});
  // HHT (Hilber, Hughes & Taylor 1977), alpha in [-1/3, 0]: rho_inf = (1 + alpha)/(1 - alpha).
  for (double alpha : {-0.05, -0.3})
    list.push_back(second_order_member("hht(" + std::to_string(alpha) + ")", Integrator::hht(alpha), 0.0, -alpha,
                                       (1.0 + alpha) / (1.0 - alpha)));
  IntegratorParameters given;
  for (double rho : {0.0, 0.5, 0.8}) {
    given.rho_inf = rho;
    // WBZ (Wood, Bossak & Zienkiewicz 1980): alpha_m = (rho - 1)/(rho + 1), alpha_f = 0.
    list.push_back(second_order_member("wbz(" + std::to_string(rho) + ")", make_integrator("wbz", given),
                                       (rho - 1.0) / (rho + 1.0), 0.0, rho));
    // Chung & Hulbert 1993, eq. 25: alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1).
    list.push_back(second_order_member("generalized_alpha(" + std::to_string(rho) + ")",
                                       make_integrator("generalized_alpha", given), (2.0 * rho - 1.0) / (rho + 1.0),
                                       rho / (rho + 1.0), rho));
  }
  return list;
}

/// The characteristic polynomial det(A - lambda I) of one step on u'' + omega^2 u = 0,
/// times -(1 - alpha_m + (1 - alpha_f) beta Omega^2), Omega = omega h, highest power first:
///   D lambda^3 + c2 lambda^2 + c1 lambda + c0, with
///   D  = 1 - alpha_m + (1 - alpha_f) beta Omega^2,
///   c2 = -(2 - 3 alpha_m) + Omega^2 [(1 - alpha_f)(gamma + 1/2) - (2 - 3 alpha_f) beta],
///   c1 = 1 - 3 alpha_m + Omega^2 [(1 - 3 alpha_f) beta - (1 - 2 alpha_f) gamma + 1/2],
///   c0 = alpha_m + Omega^2 alpha_f (beta - gamma + 1/2).
/// 'limit' keeps the Omega^2 parts alone: the polynomial as Omega -> infinity.
Eigen::Vector4d characteristic_polynomial(const Member& s, double omega_h, bool limit = false) {
  const double w2 = limit ? 1.0 : omega_h * omega_h, one = limit ? 0.0 : 1.0;
  return {
      one * (1.0 - s.alpha_m) + w2 * (1.0 - s.alpha_f) * s.beta,
      -one * (2.0 - 3.0 * s.alpha_m) + w2 * ((1.0 - s.alpha_f) * (s.gamma + 0.5) - (2.0 - 3.0 * s.alpha_f) * s.beta),
      one * (1.0 - 3.0 * s.alpha_m) + w2 * ((1.0 - 3.0 * s.alpha_f) * s.beta - (1.0 - 2.0 * s.alpha_f) * s.gamma + 0.5),
      one * s.alpha_m + w2 * s.alpha_f * (s.beta - s.gamma + 0.5)};
}

/// The roots of a cubic (or, with a zero leading coefficient, quadratic) through its
/// companion matrix.
std::vector<std::complex<double>> roots_of(const Eigen::Vector4d& p) {
  const int degree = p[0] != 0.0 ? 3 : 2;
  const Eigen::VectorXd monic = p.tail(degree) / p[3 - degree];
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
  companion.row(0) = -monic.transpose();
  for (int i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
  const Eigen::VectorXcd values = Eigen::EigenSolver<Eigen::MatrixXd>(companion).eigenvalues();
  return {values.data(), values.data() + values.size()};
}

double largest_modulus(const std::vector<std::complex<double>>& roots) {
  double largest = 0.0;
  for (const auto& root : roots) largest = std::max(largest, std::abs(root));
  return largest;
}

/// The principal root: the one with the largest imaginary part (the oscillation).
std::complex<double> principal(const std::vector<std::complex<double>>& roots) {
  return *std::max_element(roots.begin(), roots.end(),
                           [](const auto& a, const auto& b) { return a.imag() < b.imag(); });
}

/// The step's linear map of (u, h v, h^2 a) on u'' + omega^2 u = 0, written out from the
/// convention: (1 - alpha_m) a_{n+1} + alpha_m a_n + omega^2 [(1 - alpha_f) u_{n+1} +
/// alpha_f u_n] = 0 with Newmark's u_{n+1} and v_{n+1}.
Eigen::Matrix3d amplification_matrix(const Member& s, double omega_h) {
  const double w2 = omega_h * omega_h;
  Eigen::Matrix3d map;
  for (int j = 0; j < 3; ++j) {
    const double u = j == 0, v = j == 1, a = j == 2;  // scaled: v = h v, a = h^2 a
    const double predicted = u + v + (0.5 - s.beta) * a;
    const double a_new = -(s.alpha_m * a + w2 * ((1.0 - s.alpha_f) * predicted + s.alpha_f * u)) /
                         (1.0 - s.alpha_m + w2 * (1.0 - s.alpha_f) * s.beta);
    map.col(j) << predicted + s.beta * a_new, v + (1.0 - s.gamma) * a + s.gamma * a_new, a_new;
  }
  return map;
}

std::vector<std::complex<double>> eigenvalues(const Eigen::Matrix3d& map) {
  const Eigen::Vector3cd values = Eigen::EigenSolver<Eigen::Matrix3d>(map).eigenvalues();
  return {values.data(), values.data() + 3};
}

/// Leading term of the relative period error T_bar/T - 1 = e Omega^2 of any member: the
/// principal root is exp(i Omega + s2 Omega^2 + s3 Omega^3 + ...) with, from the
/// characteristic polynomial, s2 = 1/4 - (gamma - alpha_f + alpha_m)/2 (zero at second
/// order) and Im s3 = -e, 96 e = 11 + 48 beta + 12 gamma^2 - 36 gamma + 12 alpha_f^2 +
/// 60 alpha_m^2 - 72 alpha_f alpha_m - 72 (alpha_f - alpha_m) gamma + 60 (alpha_f - alpha_m).
/// Newmark (1/4, 1/2): 1/12 (Hughes 2000, 9.3); at second order
/// e = 1/12 + (alpha_f - alpha_m)/4 - (alpha_f - alpha_m)(3 alpha_f + alpha_m)/8
/// (HHT: 1/12 - alpha/4 - 3 alpha^2/8).
double period_error_coefficient(const Member& s) {
  const double d = s.alpha_f - s.alpha_m;
  return (11.0 + 48.0 * s.beta + 12.0 * s.gamma * s.gamma - 36.0 * s.gamma + 12.0 * s.alpha_f * s.alpha_f +
          60.0 * s.alpha_m * s.alpha_m - 72.0 * s.alpha_f * s.alpha_m - 72.0 * d * s.gamma + 60.0 * d) /
         96.0;
}

/// One NodalSpringMass node, free along x only: mass 1, spring 1 and the given dashpot.
void add_oscillator(Model& model, double damping = 0.0) {
  model.mesh().add_node({0.0, 0.0});
  SpringMassProperties properties;
  properties.mass = 1.0;
  properties.stiffness = {1.0, 0.0, 0.0};
  properties.damping = {damping, 0.0, 0.0};
  model.add_block<NodalSpringMass>("oscillator").add({0}, NodalSpringMass(properties));
  model.fix(0, kUy);
  model.fix(0, kRz);
}

/// u'' + omega^2 u = 0 (m = 1, omega = 1) started from u = 1 at rest, stepped with the
/// integrator: the displacements after each step (u_0 first).
std::vector<double> free_response(const Integrator& integrator, double omega_h, int steps) {
  Model model;
  add_oscillator(model);
  Analysis analysis(model);
  analysis.set_integrator(integrator);
  analysis.set_time_step(omega_h);
  analysis.newton_settings().residual_tolerance = 1e-13;
  analysis.set_initial_displacement(dof_index(0, kUx), 1.0);
  std::vector<double> u{1.0};
  analysis.add_step_observer(
      [&u](const Analysis& run, const StepRecord&) { u.push_back(run.state().displacement[0]); });
  analysis.advance(steps * omega_h);
  return u;
}

/// Largest |D u_{n+3} + c2 u_{n+2} + c1 u_{n+1} + c0 u_n| over the run, relative to
/// (|D| + |c2| + |c1| + |c0|) max |u|: the run follows the polynomial's recurrence.
double recurrence_defect(const std::vector<double>& u, const Eigen::Vector4d& p) {
  double worst = 0.0, scale = 0.0;
  for (double value : u) scale = std::max(scale, std::abs(value));
  for (size_t n = 0; n + 3 < u.size(); ++n)
    worst = std::max(worst, std::abs(p[0] * u[n + 3] + p[1] * u[n + 2] + p[2] * u[n + 1] + p[3] * u[n]));
  return worst / (p.cwiseAbs().sum() * scale);
}

}  // namespace

TEST_CASE("each preset gives its four numbers from alpha or rho_inf, as the literature does",
          "[dynamics][integrator]") {
  for (const Member& s : members()) {
    INFO(s.label << ": " << s.integrator.name());
    CHECK(s.integrator.alpha_m() == Approx(s.alpha_m).margin(1e-15));
    CHECK(-s.integrator.alpha() == Approx(s.alpha_f).margin(1e-15));
    CHECK(s.integrator.beta() == Approx(s.beta).epsilon(1e-15));
    CHECK(s.integrator.gamma() == Approx(s.gamma).epsilon(1e-15));
    const IntegratorFactors factors = s.integrator.factors(0.01);
    CHECK(factors.force_mass == Approx(1.0 - s.alpha_m).epsilon(1e-15));
    CHECK(factors.tangent_mass == Approx((1.0 - s.alpha_m) / (s.beta * 1e-4)).epsilon(1e-15));
    CHECK(factors.force_stiffness == Approx(1.0 - s.alpha_f).epsilon(1e-15));
    CHECK(s.integrator.old_inertia_weight() == Approx(s.alpha_m).margin(1e-15));
  }
  using Catch::Matchers::Contains;
  IntegratorParameters given;
  for (double rho : {-0.1, 1.2, std::nan("")}) {
    given.rho_inf = rho;
    CHECK_THROWS_WITH(make_integrator("generalized_alpha", given), Contains("rho_inf in [0, 1]"));
    CHECK_THROWS_WITH(make_integrator("wbz", given), Contains("rho_inf in [0, 1]"));
  }
  CHECK_THROWS_WITH(
      make_integrator("generalised_alpha", given),
      Contains("no integrator named 'generalised_alpha'") && Contains("static, newmark, hht, wbz, generalized_alpha"));
}

TEST_CASE("spectral radius at omega h -> infinity and at 0.1, 1, 10: closed form, amplification matrix and run agree",
          "[dynamics][integrator]") {
  for (const Member& s : members()) {
    INFO(s.label);
    // omega h -> infinity: the roots of the limit polynomial. A multiple root (all three
    // meet at -rho_inf for generalized-alpha) is found to about eps^(1/3) = 6e-6.
    CHECK(largest_modulus(roots_of(characteristic_polynomial(s, 0.0, true))) == Approx(s.rho_inf).margin(2e-5));
    // The matrix at omega h = 1e6 tends to it.
    CHECK(largest_modulus(eigenvalues(amplification_matrix(s, 1e6))) == Approx(s.rho_inf).margin(1e-3));
    for (double omega_h : {0.1, 1.0, 10.0}) {
      INFO("omega h = " << omega_h);
      const Eigen::Vector4d polynomial = characteristic_polynomial(s, omega_h);
      const std::vector<std::complex<double>> closed = roots_of(polynomial);
      const std::vector<std::complex<double>> matrix = eigenvalues(amplification_matrix(s, omega_h));
      const double rho = largest_modulus(closed);
      CHECK(largest_modulus(matrix) == Approx(rho).epsilon(1e-12));
      CHECK(rho <= 1.0 + 1e-14);  // unconditionally stable
      // The integrator's own run follows the polynomial's recurrence to round-off ...
      const std::vector<double> u = free_response(s.integrator, omega_h, 60);
      CHECK(recurrence_defect(u, polynomial) <= 1e-13);
      // ... and, once the spurious root has died out, decays and turns at the principal root.
      const std::complex<double> root = principal(closed);
      const double spurious = std::abs(closed[0] + closed[1] + closed[2] - 2.0 * root.real());  // the real root
      INFO("principal " << root << ", spurious " << spurious);
      if (omega_h < 10.0 && spurious < 0.7 * std::abs(root)) {
        const std::complex<double> measured = testing::fitted_root(u, 40);
        CHECK(std::abs(measured) == Approx(std::abs(root)).epsilon(1e-9));
        CHECK(std::arg(measured) == Approx(std::arg(root)).epsilon(1e-9));
      }
    }
  }
}

TEST_CASE("relative period error at small omega h: closed form's leading term, the polynomial and a run agree",
          "[dynamics][integrator]") {
  for (const Member& s : members()) {
    INFO(s.label);
    const double coefficient = period_error_coefficient(s);
    for (double omega_h : {0.1, 0.05}) {
      INFO("omega h = " << omega_h);
      const std::complex<double> root = principal(roots_of(characteristic_polynomial(s, omega_h)));
      const double exact = omega_h / std::arg(root) - 1.0;
      // The next term is of order (omega h)^4: relative 2 (omega h)^2 at most here (1.8 for
      // rho_inf = 0, below 0.5 for the others).
      CHECK(exact == Approx(coefficient * omega_h * omega_h).epsilon(2.0 * omega_h * omega_h));
    }
    // A run of 20 periods at omega h = 0.1: its zero crossings give the period.
    const double omega_h = 0.1;
    const int steps = static_cast<int>(std::lround(20.0 * 2.0 * kPi / omega_h));
    const std::vector<double> u = free_response(s.integrator, omega_h, steps);
    std::vector<double> crossings;
    for (size_t n = 0; n + 1 < u.size(); ++n)
      if ((u[n] < 0.0) != (u[n + 1] < 0.0)) crossings.push_back(omega_h * (n + u[n] / (u[n] - u[n + 1])));
    REQUIRE(crossings.size() >= 38);
    const double period = 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    const double expected = 2.0 * kPi * omega_h / std::arg(principal(roots_of(characteristic_polynomial(s, omega_h))));
    CHECK(period == Approx(expected).epsilon(2e-6));
  }
}

TEST_CASE("a generalized-alpha analysis continues from a checkpoint as it would have run on; reactions are physical",
          "[dynamics][integrator]") {
  // A damped oscillator, and a second grounded spring-mass node moved by a prescribed
  // motion: its reaction is the physical residual the step equations are turned into.
  const Integrator scheme = Integrator::generalized_alpha(0.6);
  auto build = [](Model& model) {
    add_oscillator(model, 0.2);
    model.mesh().add_node({1.0, 0.0});
    SpringMassProperties moved;
    moved.mass = 3.0;
    moved.stiffness = {50.0, 0.0, 0.0};
    model.add_block<NodalSpringMass>("moved").add({1}, NodalSpringMass(moved));
    model.fix(1, kUy);
    model.fix(1, kRz);
    model.prescribe(1, kUx, 0.01, model.add_load_function(LoadFunction([](double t) { return std::sin(3.0 * t); })));
  };
  Model whole_model, resumed_model;
  build(whole_model);
  build(resumed_model);
  Analysis whole(whole_model), resumed(resumed_model);
  for (Analysis* analysis : {&whole, &resumed}) {
    analysis->set_integrator(scheme);
    analysis->set_time_step(0.05);
    analysis->set_initial_velocity(dof_index(0, kUx), 1.0);
  }
  whole.advance(1.0);
  // Through a checkpoint file: alpha_m and M a_n are among the fields it keeps.
  testing::TempDir folder;
  const std::string file = folder.path("halfway.ckpt.h5");
  macros::write_checkpoint(file, macros::capture_checkpoint(whole, nullptr, 1, "generalized-alpha"));
  const CarriedState halfway = macros::read_checkpoint(file).analysis;
  CHECK(halfway.integrator == scheme.record());
  CHECK(halfway.integrator.alpha_m == Approx(0.2 / 1.6).epsilon(1e-15));  // (2 rho - 1)/(rho + 1)
  CHECK(halfway.old_inertia_forces.size() == whole_model.mesh().dof_count());
  whole.advance(1.0);
  resumed.restore(halfway);
  resumed.advance(1.0);
  CHECK(resumed.state().displacement == whole.state().displacement);
  CHECK(resumed.state().acceleration == whole.state().acceleration);
  CHECK(resumed.reactions() == whole.reactions());
  // The reaction at the prescribed node is the physical residual there: m a + k u at t_{n+1}.
  const State& state = whole.state();
  CHECK(whole.reactions()[dof_index(1, kUx)] ==
        Approx(3.0 * state.acceleration[dof_index(1, kUx)] + 50.0 * state.displacement[dof_index(1, kUx)])
            .epsilon(1e-12));
  // A checkpoint of another scheme is refused.
  Model other_model;
  build(other_model);
  Analysis other(other_model);
  other.set_integrator(Integrator::generalized_alpha(0.7));
  CHECK_THROWS_AS(other.restore(halfway), ModelError);
}

TEST_CASE("the deck names any preset with its rho_inf; rho_inf = 1 is average acceleration on a linear model",
          "[dynamics][integrator][lua]") {
  // Generalized-alpha with rho_inf = 1 (alpha_m = alpha_f = 1/2, beta = 1/4, gamma = 1/2) and
  // WBZ with rho_inf = 1 (Newmark itself) give the trapezoidal rule's steps on a linear
  // system started in equilibrium: the same tip motion as Newmark's, to round-off (the
  // beam's rotations stay below 1e-6 rad, its nonlinearity below round-off).
  testing::TempDir dir;
  const std::string deck = dir.write("deck.lua", R"(
local function tip_motion(integrator)
  local model = tirefe.model{ title = "cantilever" }
  local chain = {}
  for i = 0, 4 do chain[#chain + 1] = model:node{ x = i / 4, y = 0 } end
  model:section{ name = "s", EA = 1e4, GA = 1e4, EI = 1, rhoA = 1, rhoI = 1e-3 }
  model:beam{ section = "s", nodes = chain }
  model:fix{ node = chain[1] }
  model:load{ node = chain[#chain], fy = -1e-7, load_function = "constant" }
  integrator(model)
  local u = {}
  for step = 1, 40 do
    model:solve{ to = step * 0.01, dt = 0.01 }
    u[step] = model:value{ node = chain[#chain], dof = "uy" }
  end
  return u
end
local stepping = require("stepping")
local newmark = tip_motion(function(m) m:integrator{ type = "newmark" } end)
local schemes = {
  ga = tip_motion(function(m) m:integrator{ type = "generalized_alpha", rho_inf = 1 } end),
  wbz = tip_motion(function(m) stepping.integrator(m, { type = "wbz", rho_inf = 1 }) end),
  damped = tip_motion(function(m) m:integrator{ type = "generalized_alpha", rho_inf = 0.5 } end),
}
local function largest_difference(u)
  local largest, scale = 0, 0
  for i = 1, #u do
    largest = math.max(largest, math.abs(u[i] - newmark[i]))
    scale = math.max(scale, math.abs(newmark[i]))
  end
  return largest / scale
end
tirefe.check{ name = "rho_inf = 1 is Newmark", value = largest_difference(schemes.ga), expected = 0, tolerance = 1e-12 }
tirefe.check{ name = "WBZ 1 is Newmark", value = largest_difference(schemes.wbz), expected = 0, tolerance = 1e-12 }
tirefe.check{ name = "rho_inf = 0.5 damps", value = largest_difference(schemes.damped), expected = 0.5,
              tolerance = 0.4999 }  -- 1.5e-3 measured
)");
  testing::check_deck_passes(deck, dir.path("out"), 3);

  const std::string misspelt = dir.write("misspelt.lua", R"(
local model = tirefe.model{ title = "misspelt" }
model:integrator{ type = "generalised_alpha", rho_inf = 0.8 }
)");
  const testing::InProcessRun run = testing::run_deck_in_process(misspelt, dir.path("out"));
  CHECK_THAT(run.error,
             Catch::Matchers::Contains("misspelt.lua:3:") &&
                 Catch::Matchers::Contains(
                     "must be one of static, newmark, hht, wbz, generalized_alpha (got 'generalised_alpha')"));
}

TEST_CASE("docs/dynamics.md's new preset compiles into a registry line and damps to the rho_inf it is given",
          "[dynamics][integrator][docs]") {
  using P = IntegratorParameters;
  const std::vector<AlphaPreset> presets = {
#include "tirefe/doc_preset_example.inc"
  };
  REQUIRE(presets.size() == 1);
  const AlphaPreset& preset = presets[0];
  for (const AlphaPreset& known : alpha_presets()) CHECK((known.kind != preset.kind && known.name != preset.name));
  P given;
  for (double rho : {0.55, 0.8, 1.0}) {
    given.rho_inf = rho;
    const Integrator scheme(GeneralizedAlpha::make(preset.kind, preset.name, preset.parameters(given)));
    INFO(scheme.name());
    const Member member{preset.name, scheme, scheme.alpha_m(), -scheme.alpha(), scheme.beta(), scheme.gamma(), rho};
    CHECK(largest_modulus(roots_of(characteristic_polynomial(member, 0.0, true))) == Approx(rho).margin(2e-5));
    CHECK(scheme.record().kind == preset.kind);
  }
  given.rho_inf = 0.4;  // HHT's alpha -3/7: its spurious root, 3/4, would outgrow rho_inf
  CHECK_THROWS_WITH(preset.parameters(given), Catch::Matchers::Contains("alpha in [-1/3, 0]"));
}
