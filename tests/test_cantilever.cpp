// Large-deflection cantilever checks of the tread beam with the Newton driver:
// the tip-loaded elastica (elliptic integrals), the roll-up into a full circle by an
// end moment, and the quadratic convergence of Newton's method.
#include <catch2/catch.hpp>

#include <cmath>
#include <iostream>

#include "elements/tread_beam.hpp"
#include "solvers/analysis.hpp"

using namespace tirefe;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Elastica of a cantilever under a dead tip load perpendicular to its axis
/// (Bisshopp and Drucker 1945): with k^2 = (1 + sin phi0)/2 and sin psi1 = 1/(sqrt2 k),
///   sqrt(P L^2/EI) = K(k) - F(psi1, k),
///   deflection / L = 1 - 2 [E(k) - E(psi1, k)] / sqrt(P L^2/EI),
///   tip x / L = sqrt(2 sin(phi0) / (P L^2/EI)).
struct ElasticaTip {
  double tip_rotation, deflection, shortening;  // rotation [rad]; displacements / L
};

ElasticaTip elastica(double load_parameter) {
  auto load_for_rotation = [](double phi0) {
    const double k = std::sqrt(0.5 * (1.0 + std::sin(phi0)));
    const double psi1 = std::asin(1.0 / (std::sqrt(2.0) * k));
    return std::pow(std::comp_ellint_1(k) - std::ellint_1(k, psi1), 2);
  };
  double low = 1e-9, high = 0.5 * kPi - 1e-12;
  for (int i = 0; i < 200; ++i) {
    const double middle = 0.5 * (low + high);
    (load_for_rotation(middle) < load_parameter ? low : high) = middle;
  }
  const double phi0 = 0.5 * (low + high);
  const double k = std::sqrt(0.5 * (1.0 + std::sin(phi0)));
  const double psi1 = std::asin(1.0 / (std::sqrt(2.0) * k));
  const double root = std::sqrt(load_parameter);
  return {phi0, 1.0 - 2.0 * (std::comp_ellint_2(k) - std::ellint_2(k, psi1)) / root,
          1.0 - std::sqrt(2.0 * std::sin(phi0) / load_parameter)};
}

struct Cantilever {
  Model model;
  int tip = 0;
};

/// A straight cantilever of length L along x, clamped at x = 0, nearly inextensible.
/// 'slenderness' sets EA = GA = slenderness * EI / L^2.
void build_cantilever(Cantilever& cantilever, int elements, double length, double bending_stiffness,
                      double slenderness = 1e7) {
  BeamSection section;
  section.bending_stiffness = bending_stiffness;
  section.axial_stiffness = slenderness * bending_stiffness / (length * length);
  section.shear_stiffness = slenderness * bending_stiffness / (length * length);
  Model& model = cantilever.model;
  for (int i = 0; i <= elements; ++i) model.mesh().add_node({length * i / elements, 0.0});
  auto& beams = model.add_block<TreadBeam>("beam");
  for (int i = 0; i < elements; ++i)
    beams.add({i, i + 1}, TreadBeam(model.mesh().position(i), model.mesh().position(i + 1), section));
  for (int c = 0; c < kDofsPerNode; ++c) model.fix(0, c);
  cantilever.tip = elements;
}

}  // namespace

TEST_CASE("elliptic-integral elastica matches Mattiasson's tabulated tip values", "[cantilever]") {
  // Mattiasson (1981), Int. J. Numer. Meth. Eng. 17, table: vertical and horizontal
  // tip displacements / L of the tip-loaded elastica.
  const double load[] = {1.0, 2.0, 5.0, 10.0};
  const double deflection[] = {0.30172, 0.49346, 0.71379, 0.81061};
  const double shortening[] = {0.05643, 0.16064, 0.38763, 0.55500};
  for (int i = 0; i < 4; ++i) {
    const ElasticaTip tip = elastica(load[i]);
    CHECK(tip.deflection == Approx(deflection[i]).margin(1e-5));
    CHECK(tip.shortening == Approx(shortening[i]).margin(1e-5));
  }
}

TEST_CASE("tip-loaded cantilever matches the elastica to 1e-3 of L for PL^2/EI from 1 to 10", "[cantilever]") {
  const double length = 2.0, bending_stiffness = 3.0;
  for (double load_parameter : {1.0, 2.0, 5.0, 10.0}) {
    Cantilever cantilever;
    build_cantilever(cantilever, 40, length, bending_stiffness);
    const double load = load_parameter * bending_stiffness / (length * length);
    cantilever.model.add_nodal_load(cantilever.tip, kUy, -load, Model::kRampLoadFunction);
    Analysis analysis(cantilever.model);
    analysis.set_time_step(0.1);
    analysis.advance(1.0);
    const State& state = analysis.state();
    const ElasticaTip exact = elastica(load_parameter);
    INFO("PL^2/EI = " << load_parameter);
    CHECK(-state.displacement[dof_index(cantilever.tip, kUy)] / length == Approx(exact.deflection).margin(1e-3));
    CHECK(-state.displacement[dof_index(cantilever.tip, kUx)] / length == Approx(exact.shortening).margin(1e-3));
    CHECK(-state.displacement[dof_index(cantilever.tip, kRz)] == Approx(exact.tip_rotation).margin(2e-3));
    // The clamp pushes up with the whole load.
    CHECK(analysis.reactions()[dof_index(0, kUy)] == Approx(load).epsilon(1e-9));
  }
}

TEST_CASE("an end moment 2 pi EI/L rolls the cantilever into a circle; error falls as (1/N)^2", "[cantilever]") {
  const double length = 1.0, bending_stiffness = 2.0;
  double previous_error = 0.0;
  for (int elements : {8, 16, 32}) {
    Cantilever cantilever;
    build_cantilever(cantilever, elements, length, bending_stiffness);
    cantilever.model.add_nodal_load(cantilever.tip, kRz, 2.0 * kPi * bending_stiffness / length,
                                    Model::kRampLoadFunction);
    Analysis analysis(cantilever.model);
    analysis.set_time_step(0.125);
    analysis.advance(1.0);
    const State& state = analysis.state();
    const int tip = cantilever.tip;
    CHECK(state.displacement[dof_index(tip, kRz)] == Approx(2.0 * kPi).epsilon(1e-9));
    // The tip comes back to the root.
    CHECK(std::abs(length + state.displacement[dof_index(tip, kUx)]) <= 1e-6 * length);
    CHECK(std::abs(state.displacement[dof_index(tip, kUy)]) <= 1e-6 * length);
    // The middle node should sit at the top of the circle, (0, L/pi).
    const int middle = elements / 2;
    const Eigen::Vector2d position =
        cantilever.model.mesh().position(middle) + state.displacement.segment<2>(dof_index(middle, kUx));
    const double error = (position - Eigen::Vector2d(0.0, length / kPi)).norm();
    INFO("N = " << elements << ", error " << error);
    if (previous_error > 0.0) CHECK(previous_error / error == Approx(4.0).epsilon(0.05));
    previous_error = error;
  }
}

TEST_CASE("Newton converges quadratically on the large-deflection cantilever", "[cantilever][newton]") {
  Cantilever cantilever;
  // A moderately slender beam keeps the residual norm free of axial-stiffness round-off.
  build_cantilever(cantilever, 20, 1.0, 1.0, 1e3);
  cantilever.model.add_nodal_load(cantilever.tip, kUy, -10.0, Model::kRampLoadFunction);
  Analysis analysis(cantilever.model);
  analysis.newton_settings().residual_tolerance = 1e-13;
  analysis.set_log(&std::cout);
  analysis.set_time_step(0.05);
  analysis.advance(0.6);  // the last step starts from PL^2/EI = 5.5, tip rotation about 1.3 rad
  const std::vector<double> norms = analysis.last_newton_report().residual_norms;
  // In the asymptotic range |R_{k+1}| / |R_ref| <= C (|R_k| / |R_ref|)^2 with a modest C:
  // each iteration at least squares the relative residual, bar a constant.
  int quadratic_steps = 0;
  for (size_t k = 0; k + 1 < norms.size(); ++k) {
    const double current = norms[k] / norms[0], next = norms[k + 1] / norms[0];
    if (current > 1e-2 || current < 1e-6) continue;  // above round-off: next stays measurable
    INFO("iteration " << k << ": " << current << " -> " << next);
    CHECK(next <= 10.0 * current * current);
    ++quadratic_steps;
  }
  CHECK(quadratic_steps >= 1);
}
