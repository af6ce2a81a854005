// TreadBeam: tangent against finite differences, rigid-body invariance, symmetry,
// the section law on simple states, and the batch path (with its inline sine and cosine)
// against evaluate().
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "elements/sine_cosine.hpp"
#include "elements/tread_beam.hpp"
#include "test_support.hpp"

using namespace tirefe;

namespace {
BeamSection test_section() {
  BeamSection section;
  section.axial_stiffness = 3.0e5;
  section.shear_stiffness = 8.0e4;
  section.bending_stiffness = 20.0;
  section.mass_per_length = 1.7;
  section.rotary_inertia_per_length = 2.0e-4;
  section.curvature_damping = 0.3;
  return section;
}
}  // namespace

TEST_CASE("beam tangent equals central finite differences of the residual at large deformation", "[beam]") {
  std::mt19937 random(42);
  const TreadBeam beam({0.1, 0.2}, {0.13, 0.25}, test_section());
  for (int trial = 0; trial < 20; ++trial) {
    const auto local = testing::random_local_state<6>(random, 0.03, 2.0);
    double asymmetry = 0.0;
    INFO("trial " << trial);
    CHECK(testing::relative_tangent_error(beam, local, testing::dynamic_context(1e-3), &asymmetry) <= 1e-6);
    CHECK(asymmetry <= 1e-12);
    CHECK(testing::mass_times_deviation(beam, local) <= 1e-15);
  }
}

TEST_CASE("beam gives zero force under a large rigid-body motion", "[beam]") {
  const Eigen::Vector2d start(0.3, -0.1), end(0.35, 0.02);
  const TreadBeam beam(start, end, test_section());
  for (double angle : {0.3, 1.7, -2.9, 6.0}) {
    const Eigen::Rotation2Dd rotation(angle);
    const Eigen::Vector2d shift(0.7, -0.4);
    LocalState<6> local;
    local.velocity.setZero();
    local.acceleration.setZero();
    local.displacement << rotation * start + shift - start, angle, rotation * end + shift - end, angle;
    TreadBeam::Vector residual;
    NoHistory history;
    beam.evaluate(local, testing::dynamic_context(), history, history, residual, nullptr);
    CHECK(residual.norm() <= 1e-9);
  }
}

TEST_CASE("beam section forces: uniform stretch and pure bending", "[beam]") {
  const BeamSection section = test_section();
  const TreadBeam beam({0.0, 0.0}, {2.0, 0.0}, section);
  NoHistory history;
  TreadBeam::Vector residual;
  EvaluationContext statics;
  LocalState<6> local;
  local.velocity.setZero();
  local.acceleration.setZero();

  local.displacement << 0, 0, 0, 0.002, 0, 0;  // 0.1 % strain
  beam.evaluate(local, statics, history, history, residual, nullptr);
  CHECK(residual[3] == Approx(section.axial_stiffness * 0.001).epsilon(1e-12));
  CHECK(residual[0] == Approx(-section.axial_stiffness * 0.001).epsilon(1e-12));

  local.displacement << 0, 0, -0.01, 0, 0, 0.01;  // curvature 0.01 1/m, no stretch of the chord at the midpoint
  beam.evaluate(local, statics, history, history, residual, nullptr);
  CHECK(residual[5] == Approx(section.bending_stiffness * 0.01).epsilon(1e-12));
  CHECK(residual[2] == Approx(-section.bending_stiffness * 0.01).epsilon(1e-12));
}

TEST_CASE("beam kinetic energy of a rigid translation is half m v^2", "[beam]") {
  const BeamSection section = test_section();
  const TreadBeam beam({0.0, 0.0}, {0.4, 0.3}, section);  // length 0.5
  LocalState<6> local;
  local.displacement.setZero();
  local.acceleration.setZero();
  local.velocity << 3.0, -4.0, 0.0, 3.0, -4.0, 0.0;  // speed 5 m/s
  const ElementEnergy energy = beam.energy(local, NoHistory{});
  CHECK(energy.kinetic == Approx(0.5 * section.mass_per_length * 0.5 * 25.0).epsilon(1e-12));
  CHECK(energy.strain == Approx(0.0).margin(1e-15));
}

TEST_CASE("beam rejects non-physical sections", "[beam]") {
  BeamSection section = test_section();
  section.bending_stiffness = -1.0;
  CHECK_THROWS_WITH(TreadBeam({0, 0}, {1, 0}, section), Catch::Contains("EI"));
  CHECK_THROWS_WITH(TreadBeam({0, 0}, {0, 0}, test_section()), Catch::Contains("zero length"));
}

TEST_CASE("sine_cosine: within two units in the last place of std::sin and std::cos up to 1e5 rad", "[beam]") {
  std::mt19937 random(3);
  double worst = 0.0;
  for (double range : {1.0, 10.0, 1e3, 1e5}) {
    std::uniform_real_distribution<double> uniform(-range, range);
    for (int i = 0; i < 100000; ++i) {
      const double angle = uniform(random);
      const SineCosine value = sine_cosine(angle);
      worst = std::max({worst, std::abs(value.sin - std::sin(angle)), std::abs(value.cos - std::cos(angle))});
    }
  }
  // Multiples of pi/4 (quadrant ends and middles) and a rolling belt's turns.
  for (int k = -4000; k <= 4000; ++k)
    for (double shift : {0.0, 1e-9, -3e-13}) {
      const double angle = k * 0.78539816339744830962 + shift;
      const SineCosine value = sine_cosine(angle);
      worst = std::max({worst, std::abs(value.sin - std::sin(angle)), std::abs(value.cos - std::cos(angle))});
    }
  CHECK(worst <= 2.3e-16);
  CHECK(sine_cosine(0.0).sin == 0.0);
  CHECK(sine_cosine(0.0).cos == 1.0);
}

TEST_CASE("beam batch path: every beam of a perturbed, rolled ring as evaluate() gives it, to 1e-14", "[beam]") {
  // 100 beams round a circle, some without damping or rotary inertia, deformed by
  // millimetres and turned by hundreds of radians (a rolling belt), each state in turn
  // static, Newmark and HHT, with and without the tangent.
  std::mt19937 random(5);
  constexpr int kBeams = 100;
  constexpr double kPi = 3.14159265358979323846;
  std::vector<TreadBeam> beams;
  std::vector<LocalState<6>> locals;
  for (int e = 0; e < kBeams; ++e) {
    BeamSection section = test_section();
    if (e % 7 == 3) section.curvature_damping = section.rotary_inertia_per_length = 0.0;
    section.axial_stiffness *= 1.0 + 0.01 * e;
    const double angle = 2.0 * kPi * e / kBeams, next = 2.0 * kPi * (e + 1) / kBeams;
    beams.emplace_back(Eigen::Vector2d(0.3 * std::cos(angle), 0.3 * std::sin(angle)),
                       Eigen::Vector2d(0.3 * std::cos(next), 0.3 * std::sin(next)), section);
    LocalState<6> local = testing::random_local_state<6>(random, 0.003, 0.05);
    local.displacement[2] += 2.7 * e - 150.0;
    local.displacement[5] += 2.7 * e - 150.0;
    local.velocity *= 20.0;
    locals.push_back(local);
  }
  for (const EvaluationContext& context : testing::batch_contexts())
    for (bool with_tangent : {true, false}) {
      INFO("tangent " << with_tangent << ", mass factor " << context.factors.tangent_mass);
      CHECK(testing::batch_deviation(beams, locals, context, with_tangent) <= 1e-14);
    }
  // The stored energy the energy balance books each step, summed over the block.
  CHECK(testing::batch_energy_deviation(beams, locals) <= 1e-14);
}
