// TreadBeam: tangent against finite differences, rigid-body invariance, symmetry,
// and the section law on simple states.
#include <catch2/catch.hpp>

#include <cmath>

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
