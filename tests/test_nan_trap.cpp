// NaN traps: an element whose residual turns NaN stops the Newton solve at once, and the
// step failure names the block, the element and the node and DOF that produced it.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "elements/tread_beam.hpp"
#include "solvers/analysis.hpp"

namespace {

using namespace tirefe;

// A linear spring between two nodes along x whose force turns NaN on its second node
// beyond a stretch: a stand-in for a material law leaving its domain.
struct BreakingSpring : KernelShape<2> {
  double stiffness = 100.0, breaking_stretch = 0.0533;
  void evaluate(const LocalState<kDofs>& local, const EvaluationContext& context, const History&, History&,
                Vector& residual, Matrix* tangent) const {
    const double stretch = local.displacement[3] - local.displacement[0];
    residual.setZero();
    residual[0] = -stiffness * stretch * context.factors.force_stiffness;
    residual[3] = stretch > breaking_stretch ? std::numeric_limits<double>::quiet_NaN()
                                             : stiffness * stretch * context.factors.force_stiffness;
    if (tangent) {
      tangent->setZero();
      (*tangent)(0, 0) = (*tangent)(3, 3) = stiffness * context.factors.tangent_stiffness;
      (*tangent)(0, 3) = (*tangent)(3, 0) = -stiffness * context.factors.tangent_stiffness;
      (*tangent)(1, 1) = (*tangent)(2, 2) = (*tangent)(4, 4) = (*tangent)(5, 5) = 1.0;  // keep it regular
    }
  }
  ElementEnergy energy(const LocalState<kDofs>&, const History&) const { return {}; }
};

}  // namespace

TEST_CASE("a NaN in an element residual names the block, element, node and DOF", "[reliability][nan]") {
  Model model;
  for (int i = 0; i < 3; ++i) model.mesh().add_node({static_cast<double>(i), 0.0});
  auto& springs = model.add_block<BreakingSpring>("springs");
  BreakingSpring stiff;
  stiff.stiffness = 1000.0;
  springs.add({0, 1}, stiff);
  springs.add({1, 2}, BreakingSpring{});
  model.fix(0, 0);
  // The load f = t stretches the springs by f/k: the second one (nodes 2 and 3 in deck
  // numbering) by 0.01 per unit of load level, so it breaks beyond a level of 5.33.
  model.add_nodal_load(2, 0, 1.0, Model::kRampLoadFunction);
  Analysis analysis(model);
  analysis.step_control().max_cuts = 2;
  analysis.set_time_step(1.0);
  analysis.advance(4.0);  // below the breaking level: fine
  CHECK(analysis.state().displacement[dof_index(2, 0)] == Approx(0.044));
  try {
    analysis.advance(2.0);
    FAIL("the NaN went unnoticed");
  } catch (const StepFailure& failure) {
    const std::string message = failure.what();
    INFO(message);
    CHECK(message.find("element 2 of block 'springs' (nodes 2, 3) produced a non-finite residual at node 3, ux") !=
          std::string::npos);
  }
  // The failed step left the committed state untouched, and finite.
  CHECK(analysis.state().time >= 4.0);
  CHECK(analysis.state().time < 5.33);
  CHECK(analysis.state().displacement.allFinite());
}

TEST_CASE("a NaN in a batched block's residual names its element, node and DOF too", "[reliability][nan]") {
  // Three tread beams in a row (a batch kernel); a NaN displacement at the third node
  // makes the second and third beams' residuals NaN: the second is named, at its node.
  Model model;
  for (int i = 0; i < 4; ++i) model.mesh().add_node({0.1 * i, 0.0});
  BeamSection section;
  section.axial_stiffness = section.shear_stiffness = 1e5;
  section.bending_stiffness = 10.0;
  section.mass_per_length = 1.0;
  auto& beams = model.add_block<TreadBeam>("beams");
  for (int i = 0; i < 3; ++i)
    beams.add({i, i + 1}, TreadBeam(model.mesh().position(i), model.mesh().position(i + 1), section));
  Assembler assembler(model);
  assembler.update_pattern();
  State state;
  state.resize(model.mesh().dof_count());
  state.displacement[dof_index(2, 1)] = std::numeric_limits<double>::quiet_NaN();
  EvaluationContext context;
  context.factors = Integrator::internal_force_factors();
  context.want_tangent = true;
  Eigen::VectorXd residual;
  try {
    assembler.query(context, state, residual);
    FAIL("the NaN went unnoticed");
  } catch (const NonFiniteResult& failure) {
    const std::string message = failure.what();
    INFO(message);
    CHECK(message.find("element 2 of block 'beams' (nodes 2, 3) produced a non-finite residual at node 2") !=
          std::string::npos);
  }
}

TEST_CASE("all_finite finds a NaN or an infinity anywhere, and passes every finite value", "[reliability][nan]") {
  constexpr double kMax = std::numeric_limits<double>::max();
  std::vector<double> values(37);
  for (size_t k = 0; k < values.size(); ++k) values[k] = (k % 2 ? -1.0 : 1.0) * std::pow(10.0, double(k) - 18.0);
  values[3] = kMax;
  values[4] = -kMax;
  values[5] = std::numeric_limits<double>::denorm_min();
  values[6] = -0.0;
  CHECK(all_finite(values.data(), static_cast<int>(values.size())));
  CHECK(all_finite(values.data(), 0));
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()})
    for (size_t at : {size_t(0), size_t(17), values.size() - 1}) {
      std::vector<double> spoiled = values;
      spoiled[at] = bad;
      CHECK_FALSE(all_finite(spoiled.data(), static_cast<int>(spoiled.size())));
    }
}
