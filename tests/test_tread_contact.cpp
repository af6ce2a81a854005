// TreadContact, the tire's tread against a surface through its massless tread rubber
// (contact/tread_contact.hpp): the tangent against central differences (stick, slip and
// landing, with the dashpots, on a moving tilted road, a spinning drum and a rounded edge),
// the closed forms of a chord pressed and sheared on a road, frame indifference on a moving
// road and a spinning drum, no slip booked where the closest point jumps inside a corner,
// and the energy balance of a chord dropped on a moving road, closed as the step shrinks.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>

#include "contact/tread_contact.hpp"
#include "elements/point_mass.hpp"
#include "elements/tread_beam.hpp"
#include "solvers/analysis.hpp"
#include "test_support.hpp"

using namespace tirefe;

namespace {

using Local = LocalState<TreadContact::kDofs>;

TreadRubber rubber(double friction, double normal_damping = 0.0, double tangential_damping = 0.0) {
  TreadRubber law;
  law.normal_stiffness = 1e7;
  law.tangential_stiffness = 6e6;
  law.normal_damping = normal_damping;
  law.tangential_damping = tangential_damping;
  law.friction = friction;
  return law;
}

Local local_state(const Eigen::Vector2d& ua, const Eigen::Vector2d& ub, const Eigen::Vector2d& va = {0.0, 0.0},
                  const Eigen::Vector2d& vb = {0.0, 0.0}) {
  Local local;
  local.displacement << ua, 0.0, ub, 0.0;
  local.velocity << va, 0.0, vb, 0.0;
  local.acceleration.setZero();
  return local;
}

/// Evaluates the kernel at 'local' from 'base'; returns the residual (and the trial history).
TreadContact::Vector evaluate(const TreadContact& kernel, const Local& local, const EvaluationContext& context,
                              const TreadContact::History& base, TreadContact::History& trial,
                              TreadContact::Matrix* tangent = nullptr) {
  TreadContact::Vector residual;
  kernel.evaluate(local, context, base, trial, residual, tangent);
  return residual;
}

/// The kernel's tangent against central differences: (cK/wK) dr/du + (cC/wK) dr/dv, its
/// whole force being weighted by wK (wC = wK wherever the dashpots act).
void check_tangent(const TreadContact& kernel, const Local& local, const EvaluationContext& context,
                   const TreadContact::History& base, double tolerance = 1e-6) {
  TreadContact::History trial = base;
  TreadContact::Matrix tangent;
  evaluate(kernel, local, context, base, trial, &tangent);
  TreadContact::Matrix numeric = TreadContact::Matrix::Zero();
  const double step = 1e-9;
  const IntegratorFactors& f = context.factors;
  for (int j = 0; j < TreadContact::kDofs; ++j) {
    for (auto field : {&Local::displacement, &Local::velocity}) {
      const double factor =
          (field == &Local::displacement ? f.tangent_stiffness : f.tangent_damping) / f.force_stiffness;
      if (factor == 0.0) continue;
      Local plus = local, minus = local;
      (plus.*field)[j] += step;
      (minus.*field)[j] -= step;
      TreadContact::History scratch = base;
      const TreadContact::Vector up = evaluate(kernel, plus, context, base, scratch);
      const TreadContact::Vector down = evaluate(kernel, minus, context, base, scratch);
      numeric.col(j) += factor * (up - down) / (2.0 * step);
    }
  }
  INFO("tangent\n" << tangent << "\nfinite differences\n" << numeric);
  REQUIRE(tangent.norm() > 0.0);
  CHECK((tangent - numeric).norm() <= tolerance * tangent.norm());
  for (int idle : {2, 5}) {
    CHECK(tangent.row(idle).isZero());
    CHECK(tangent.col(idle).isZero());
  }
}

int count(const TreadContact::History& history, ContactState state) {
  int n = 0;
  for (const TreadSample& sample : history) n += sample.state == state;
  return n;
}

EvaluationContext at(double time, double step = 1e-3) {
  EvaluationContext context = testing::dynamic_context(step);
  context.time = time;
  context.factors.force_stiffness = context.factors.force_damping = 0.95;  // HHT-like weights
  context.factors.tangent_stiffness = 0.95;
  context.factors.tangent_damping *= 0.95;
  return context;
}

}  // namespace

TEST_CASE("tread contact tangent equals finite differences: stick, slip and landing, with dashpots",
          "[contact][tread][tangent]") {
  // A tilted road that translates and turns; a chord 17 mm long sunk 2-3 mm into it.
  auto road = std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 0.1),
                                         RigidMotion(MotionFunction::linear(0.4), MotionFunction::linear(0.02),
                                                     MotionFunction::linear(0.3), Eigen::Vector2d(0.5, 0.0)));
  const Eigen::Vector2d a(0.0, 0.0), b(0.017, 0.0017);
  const TreadContact kernel(road, a, b, rubber(0.6, 2.4e3, 2.4e3));
  // The step's start: the chord sunk 2 mm, sticking where it landed.
  const Eigen::Vector2d down = -0.002 * road->project(a, 0.0).normal;
  TreadContact::History base{}, start{};
  evaluate(kernel, local_state(down, down), at(0.0), start, base);
  REQUIRE(count(base, ContactState::Stick) == TreadContact::kSamples);
  const Eigen::Vector2d va(0.3, -0.2), vb(0.25, -0.1);

  SECTION("stick: a small travel along the road") {
    const Local local = local_state(down + Eigen::Vector2d(4e-4, -5e-4), down + Eigen::Vector2d(4.2e-4, -7e-4), va, vb);
    TreadContact::History trial = base;
    evaluate(kernel, local, at(1e-3), base, trial);
    CHECK(count(trial, ContactState::Stick) == TreadContact::kSamples);
    check_tangent(kernel, local, at(1e-3), base);
  }
  SECTION("slip, both ways") {
    for (const double along : {6e-3, -6e-3}) {
      const Local local =
          local_state(down + Eigen::Vector2d(along, -5e-4), down + Eigen::Vector2d(along, -7e-4), va, vb);
      TreadContact::History trial = base;
      evaluate(kernel, local, at(1e-3), base, trial);
      CHECK(count(trial, ContactState::Slip) == TreadContact::kSamples);
      check_tangent(kernel, local, at(1e-3), base);
    }
  }
  SECTION("landing: open when the step began, sunk at its end; some samples clear") {
    TreadContact::History open{};
    const Local local = local_state(down, Eigen::Vector2d(0.0, 0.001), va, vb);
    TreadContact::History trial = open;
    evaluate(kernel, local, at(1e-3), open, trial);
    CHECK(count(trial, ContactState::Open) > 0);
    CHECK(count(trial, ContactState::Open) < TreadContact::kSamples);
    check_tangent(kernel, local, at(1e-3), open);
  }
  SECTION("quasi-statically the dashpots are off") {
    EvaluationContext statics = at(1e-3);
    statics.factors = IntegratorFactors{};
    const Local local = local_state(down + Eigen::Vector2d(4e-4, -5e-4), down + Eigen::Vector2d(4.2e-4, -7e-4), va, vb);
    TreadContact::History moving = base, resting = base;
    const TreadContact::Vector r1 = evaluate(kernel, local, statics, base, moving);
    const TreadContact::Vector r2 =
        evaluate(kernel, local_state(local.displacement.segment<2>(0), local.displacement.segment<2>(3)), statics, base,
                 resting);
    CHECK((r1 - r2).norm() == 0.0);
    check_tangent(kernel, local, statics, base);
  }
}

TEST_CASE("tread contact tangent equals finite differences on a spinning drum and on a rounded edge",
          "[contact][tread][tangent]") {
  SECTION("a spinning drum: its curvature and spin") {
    const double radius = 0.85;
    auto drum = std::make_shared<Drum>(2.0 * radius, Eigen::Vector2d(0.0, -radius), MotionFunction::linear(-16.0));
    const Eigen::Vector2d a(-0.0085, 0.0), b(0.0085, 0.0);
    const TreadContact kernel(drum, a, b, rubber(0.5, 2.4e3, 2.4e3));
    TreadContact::History base{}, start{};
    evaluate(kernel, local_state({0.0, -0.003}, {0.0, -0.003}), at(0.0), start, base);
    for (const double along : {2e-4, 8e-3}) {  // stick, then slip
      const Local local = local_state({along, -0.0032}, {along + 1e-4, -0.0035}, {13.0, -0.4}, {13.1, -0.3});
      check_tangent(kernel, local, at(1e-3), base, 2e-6);
    }
  }
  SECTION("a cleat's rounded edge under the chord") {
    const double r = 0.005;
    auto road = std::make_shared<RoadProfile>(RoadProfile::cleat_points(0.0, 0.1, 0.02), r,
                                              RigidMotion::translation(MotionFunction::linear(-1.0)));
    const Eigen::Vector2d a(-0.012, 0.0215), b(0.005, 0.0215);  // above the front edge at t = 0.01
    const TreadContact kernel(road, a, b, rubber(0.4, 2.4e3, 1e3));
    TreadContact::History base{}, start{};
    evaluate(kernel, local_state({0.0, -0.003}, {0.0, -0.003}), at(0.01), start, base);
    REQUIRE(count(base, ContactState::Open) < TreadContact::kSamples);
    const Local local = local_state({1e-4, -0.0033}, {2e-4, -0.0034}, {0.2, -0.5}, {0.1, -0.4});
    check_tangent(kernel, local, at(0.011), base, 2e-6);
  }
}

TEST_CASE("a chord pressed into a road carries k_N times its compression, sheared k_T times its travel",
          "[contact][tread]") {
  // A chord of length L = 20 mm on a still flat road, statically.
  auto road = std::make_shared<FlatRoad>();
  const double length = 0.02, k_n = 1e7, k_t = 6e6, mu = 0.5;
  const TreadContact kernel(road, {0.0, 0.0}, {length, 0.0}, rubber(mu));
  EvaluationContext statics;
  TreadContact::History none{}, pressed{};

  SECTION("evenly: each node carries half of k_N L d; the layer stores k_N L d^2 / 2") {
    const double d = 0.003;
    const TreadContact::Vector r = evaluate(kernel, local_state({0.0, -d}, {0.0, -d}), statics, none, pressed);
    CHECK(r[1] == Approx(-0.5 * k_n * length * d).epsilon(1e-12));
    CHECK(r[4] == Approx(-0.5 * k_n * length * d).epsilon(1e-12));
    CHECK(std::abs(r[0]) + std::abs(r[3]) <= 1e-9);
    CHECK(kernel.energy(local_state({0.0, -d}, {0.0, -d}), pressed).strain ==
          Approx(0.5 * k_n * length * d * d).epsilon(1e-12));
  }
  SECTION("tilted: the total is exact, each node's share within the midpoint rule's error") {
    const double da = 0.001, db = 0.004;
    const TreadContact::Vector r = evaluate(kernel, local_state({0.0, -da}, {0.0, -db}), statics, none, pressed);
    // Of k_N L (d_a (1 - xi) + d_b xi) shared as (1 - xi) and xi: L k_N (d_a/3 + d_b/6), L k_N (d_a/6 + d_b/3).
    CHECK(-(r[1] + r[4]) == Approx(k_n * length * 0.5 * (da + db)).epsilon(1e-12));
    // The midpoint rule's error on a quadratic f over Q intervals: |f''| / (24 Q^2), here
    // f'' = 2 k_N L (d_b - d_a) for either share.
    const double midpoint_error =
        2.0 * k_n * length * (db - da) / (24.0 * TreadContact::kSamples * TreadContact::kSamples) * (1.0 + 1e-9);
    CHECK(-r[1] == Approx(k_n * length * (da / 3 + db / 6)).margin(midpoint_error));
    CHECK(-r[4] == Approx(k_n * length * (da / 6 + db / 3)).margin(midpoint_error));
  }
  SECTION("sheared: k_T L times the travel while it sticks, then mu N") {
    const double d = 0.002;
    evaluate(kernel, local_state({0.0, -d}, {0.0, -d}), statics, none, pressed);  // lands unsheared
    REQUIRE(count(pressed, ContactState::Stick) == TreadContact::kSamples);
    const double normal = k_n * length * d;
    const double stick_limit = mu * normal / (k_t * length);  // the travel at which it slips
    for (const double travel : {0.3 * stick_limit, 0.9 * stick_limit, 3.0 * stick_limit}) {
      TreadContact::History trial = pressed;
      const TreadContact::Vector r = evaluate(kernel, local_state({travel, -d}, {travel, -d}), statics, pressed, trial);
      const double expected = std::min(k_t * length * travel, mu * normal);
      CHECK(r[0] + r[3] == Approx(expected).epsilon(1e-12));  // the residual is -f: it resists
      CHECK(count(trial, travel < stick_limit ? ContactState::Stick : ContactState::Slip) == TreadContact::kSamples);
      // Slipping, the rubber keeps the shear of mu N; the rest of the travel is dissipated.
      const double shear = std::min(travel, stick_limit);
      const ElementEnergy energy = kernel.energy(local_state({travel, -d}, {travel, -d}), trial);
      CHECK(energy.strain == Approx(0.5 * length * (k_n * d * d + k_t * shear * shear)).epsilon(1e-12));
      CHECK(energy.dissipated == Approx(mu * normal * (travel - shear)).epsilon(1e-12).margin(1e-15));
    }
  }
}

TEST_CASE("tread contact is frame-indifferent: carried with the surface, it shears nothing",
          "[contact][tread][moving]") {
  SECTION("a road translating and turning, the chord carried with it") {
    const RigidMotion motion(MotionFunction::linear(0.7), MotionFunction::linear(0.1), MotionFunction::linear(0.5),
                             Eigen::Vector2d(0.2, 0.0));
    auto road = std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 0.0), motion);
    const Eigen::Vector2d a(0.0, 0.0), b(0.017, 0.0);
    const TreadContact kernel(road, a, b, rubber(0.8, 2.4e3, 2.4e3));
    const Eigen::Vector2d sunk(0.0, -0.002);
    TreadContact::History history{};
    for (int step = 0; step <= 20; ++step) {
      const double t = 0.01 * step;
      // The chord's points carried rigidly with the road, and their velocities.
      auto carried = [&](const Eigen::Vector2d& x) -> Eigen::Vector2d { return motion.to_space(x + sunk, t) - x; };
      const Local local =
          local_state(carried(a), carried(b), motion.velocity(carried(a) + a, t), motion.velocity(carried(b) + b, t));
      TreadContact::History trial = history;
      evaluate(kernel, local, at(t, 0.01), history, trial);
      history = trial;
      for (const TreadSample& sample : history) {
        CHECK(sample.state == ContactState::Stick);
        CHECK(std::abs(sample.tangential_force) <= 1e-9);
        CHECK(std::abs(sample.sliding_velocity) <= 1e-12);
        CHECK(sample.normal_force == Approx(1e7 * 0.017 / 8 * 0.002).epsilon(1e-9));
      }
    }
  }
  SECTION("a chord sunk into a spinning drum and turning with it") {
    const double radius = 0.85, spin = -16.0;
    auto drum = std::make_shared<Drum>(2.0 * radius, Eigen::Vector2d::Zero(), MotionFunction::linear(spin));
    const Eigen::Vector2d a(-0.0085, radius + 0.0), b(0.0085, radius + 0.0);
    const TreadContact kernel(drum, a, b, rubber(0.8, 2.4e3, 2.4e3));
    TreadContact::History history{};
    for (int step = 0; step <= 20; ++step) {
      const double t = 0.001 * step, c = std::cos(spin * t), s = std::sin(spin * t);
      const Eigen::Matrix2d turn = (Eigen::Matrix2d() << c, -s, s, c).finished();
      const Eigen::Vector2d sink(0.0, -0.003);
      auto at_time = [&](const Eigen::Vector2d& x) { return Eigen::Vector2d(turn * (x + sink) - x); };
      auto velocity = [&](const Eigen::Vector2d& x) {
        return Eigen::Vector2d(spin * Eigen::Vector2d(-(turn * (x + sink)).y(), (turn * (x + sink)).x()));
      };
      const Local local = local_state(at_time(a), at_time(b), velocity(a), velocity(b));
      TreadContact::History trial = history;
      evaluate(kernel, local, at(t), history, trial);
      history = trial;
      for (const TreadSample& sample : history) {
        CHECK(sample.state == ContactState::Stick);
        CHECK(std::abs(sample.tangential_force) <= 1e-6);
        CHECK(std::abs(sample.sliding_velocity) <= 1e-9);
      }
    }
  }
}

TEST_CASE("a sample crossing the bisector inside a corner books no slip for its closest point's jump",
          "[contact][tread][vertex]") {
  // A chord 8 mm inside a cleat's sharp top-front corner (the cleat's top at y = 20 mm, its
  // front at x = 0), moved by 1 mm across the corner's bisector: the closest point jumps from
  // the front face to the top, 16 mm along the surface, but the chord travelled 1 mm.
  auto road = std::make_shared<RoadProfile>(RoadProfile::cleat_points(0.0, 0.1, 0.02));
  const double half = 0.5e-3;
  const Eigen::Vector2d a(0.008 - 0.0005, 0.012 - half), b(0.008 + 0.0005, 0.012 + half);
  const TreadContact kernel(road, a, b, rubber(0.3));
  EvaluationContext statics;
  TreadContact::History none{}, before{}, after{};
  const Eigen::Vector2d shift(0.0, -0.0015);  // across the bisector y = 0.02 - x, from the front side to the top side
  evaluate(kernel, local_state({0.0, 0.0}, {0.0, 0.0}), statics, none, before);
  evaluate(kernel, local_state(shift, shift), statics, before, after);
  double jump = 0.0;
  for (int q = 0; q < TreadContact::kSamples; ++q)
    jump = std::max(jump, std::abs(road->arc_difference(after[q].coordinate, before[q].coordinate)));
  REQUIRE(jump > 0.01);  // some sample's closest point went round the corner
  const double moved = shift.norm();
  for (int q = 0; q < TreadContact::kSamples; ++q) {
    CHECK(std::abs(after[q].shear - before[q].shear) <= moved * (1.0 + 1e-9));
    // Whatever slip is booked is at most the friction over the travel.
    CHECK(after[q].dissipated - before[q].dissipated <= 0.3 * after[q].normal_force * moved * (1.0 + 1e-9));
  }
}

namespace {

/// A chord of two point masses joined by a beam, its rotations held, dropped from 'height'
/// onto a road moving at 'speed' under gravity, with friction and the rubber's dashpots:
/// the energy balance's error over 0.2 s relative to what friction and the dashpots took.
double dropped_chord_balance(double step, double* dissipated = nullptr) {
  Model model;
  const double length = 0.03, height = 0.002, speed = 2.0;
  const int a = model.mesh().add_node({0.0, height}), b = model.mesh().add_node({length, height});
  SpringMassProperties point;
  point.mass = 0.05;
  auto& masses = model.add_block<NodalSpringMass>("masses");
  masses.add({a}, NodalSpringMass(point));
  masses.add({b}, NodalSpringMass(point));
  BeamSection section;
  section.axial_stiffness = 1e6;
  section.shear_stiffness = 1e5;
  section.bending_stiffness = 5.0;
  section.mass_per_length = 0.1;
  section.rotary_inertia_per_length = 1e-5;
  model.add_block<TreadBeam>("beam").add({a, b}, TreadBeam({0.0, height}, {length, height}, section));
  auto road = std::make_shared<FlatRoad>(Eigen::Vector2d::Zero(), Eigen::Vector2d::UnitX(),
                                         RigidMotion::translation(MotionFunction::ramped_rate(speed, 0.05, 0.02)));
  model.add_block<TreadContact>("contact").add(
      {a, b}, TreadContact(road, {0.0, height}, {length, height}, rubber(0.6, 2.4e3, 2.4e3)));
  for (int node : {a, b}) {
    model.fix(node, kRz);
    model.add_nodal_load(node, kUy, -50.0, model.add_load_function(LoadFunction::constant(1.0)));
  }
  Analysis analysis(model);
  analysis.set_integrator(Integrator::newmark());
  analysis.set_time_step(step);
  analysis.advance(0.2);
  const EnergyRecord& energy = analysis.energy();
  if (dissipated) *dissipated = energy.contact_dissipated + energy.damping;
  return energy.balance_error;
}

}  // namespace

TEST_CASE("the energy balance of a chord dropped on a moving road closes as the step shrinks",
          "[contact][tread][energy]") {
  // It lands, bounces on its rubber, is dragged up to speed by friction and rides along.
  double dissipated = 0.0;
  const double coarse = dropped_chord_balance(1e-4, &dissipated);
  const double fine = dropped_chord_balance(2.5e-5);
  INFO("dissipated " << dissipated << " J; error " << coarse << " J at 0.1 ms, " << fine << " J at 0.025 ms");
  REQUIRE(dissipated > 0.05);
  CHECK(std::abs(coarse) < 0.01 * dissipated);
  CHECK(std::abs(fine) < 0.25 * std::abs(coarse) + 1e-6 * dissipated);
}
