// The assembled tire: inflation equilibrium, and the hub-fixed belt modes against the
// rigid-ring formulas built from the sidewall element's own foundation stiffness.
#include <catch2/catch.hpp>

#include <cmath>

#include "macros/macro_table.hpp"
#include "solvers/analysis.hpp"
#include "solvers/modal.hpp"
#include "tire/tire_builder.hpp"

using namespace tirefe;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct InflatedTire {
  Model model;
  Tire tire;
  std::unique_ptr<Analysis> analysis;

  InflatedTire() {
    tire = build_tire(model, macros::load_tire_parameters("tires.145SR12"), LoadFunction::linear());
    for (int c = 0; c < kDofsPerNode; ++c) model.fix(tire.spindle, c);
    analysis = std::make_unique<Analysis>(model);
    analysis->set_time_step(0.25);
    analysis->advance(1.0);
  }
};

/// Modal assurance criterion of a mode shape against a reference field (tread nodes only).
double mac(const Eigen::VectorXd& shape, const Eigen::VectorXd& reference) {
  const double cross = shape.dot(reference);
  return cross * cross / (shape.squaredNorm() * reference.squaredNorm());
}

}  // namespace

TEST_CASE("the inflated 145 SR-12 is round, in equilibrium, with a tensioned belt", "[tire]") {
  InflatedTire inflated;
  const State& state = inflated.analysis->state();
  const double radius = 0.5 * inflated.tire.parameters.outer_diameter;
  double smallest = 1e9, largest = 0.0;
  for (int node : inflated.tire.tread_nodes) {
    const Eigen::Vector2d x = inflated.model.mesh().position(node) + state.displacement.segment<2>(dof_index(node, 0));
    smallest = std::min(smallest, x.norm());
    largest = std::max(largest, x.norm());
  }
  CHECK((largest - smallest) / radius <= 1e-12);
  CHECK(largest > radius);  // the belt is in tension: the tire grows
  CHECK(inflated.analysis->reactions().segment<2>(dof_index(inflated.tire.spindle, 0)).norm() <= 1e-8);
  CHECK(inflated.analysis->accepted_steps() == 4);
  CHECK(inflated.analysis->last_newton_report().iterations <= 4);
}

TEST_CASE("hub-fixed inflated tire: belt rotation (n = 0) and translation (n = 1) modes match the rigid ring",
          "[tire][modal]") {
  InflatedTire inflated;
  const Model& model = inflated.model;
  const State& state = inflated.analysis->state();
  const TireParameters& parameters = inflated.tire.parameters;

  // Foundation stiffness per unit length of one wedge at the inflated state: move both
  // tread nodes by the same small vector (radial or tangential at the wedge middle) and
  // difference the force the sidewall puts on them.
  const auto& sidewalls = dynamic_cast<const ElementBlockOf<SidewallWedge>&>(model.block("tire_sidewall"));
  const SidewallWedge& wedge = sidewalls.kernel(0);
  const std::vector<int> nodes = sidewalls.element_nodes(0);
  LocalState<9> local;
  local.velocity.setZero();
  local.acceleration.setZero();
  for (int n = 0; n < 3; ++n)
    local.displacement.segment<3>(3 * n) = state.displacement.segment<3>(dof_index(nodes[n], 0));
  const Eigen::Vector2d xa = model.mesh().position(nodes[1]) + local.displacement.segment<2>(3);
  const Eigen::Vector2d xb = model.mesh().position(nodes[2]) + local.displacement.segment<2>(6);
  const double chord = (xb - xa).norm();
  const Eigen::Vector2d radial = (0.5 * (xa + xb)).normalized();
  const Eigen::Vector2d tangential(-radial.y(), radial.x());
  EvaluationContext statics;
  statics.time = 1.0;
  statics.want_tangent = false;
  auto foundation_stiffness = [&](const Eigen::Vector2d& direction) {
    const double step = 1e-7;
    Eigen::Vector2d force_change = Eigen::Vector2d::Zero();
    for (double sign : {1.0, -1.0}) {
      LocalState<9> moved = local;
      moved.displacement.segment<2>(3) += sign * step * direction;
      moved.displacement.segment<2>(6) += sign * step * direction;
      SidewallWedge::Vector residual;
      NoHistory history;
      wedge.evaluate(moved, statics, history, history, residual, nullptr);
      force_change += sign * (residual.segment<2>(3) + residual.segment<2>(6));  // restoring force = residual
    }
    return direction.dot(force_change) / (2.0 * step * chord);
  };
  const double radial_stiffness = foundation_stiffness(radial);          // k_r [N/m^2]
  const double tangential_stiffness = foundation_stiffness(tangential);  // k_t [N/m^2]
  // The inward pull F of the inflated sidewall per unit length [N/m].
  SidewallWedge::Vector inflated_residual;
  NoHistory history;
  wedge.evaluate(local, statics, history, history, inflated_residual, nullptr);
  const double pull = radial.dot(inflated_residual.segment<2>(3) + inflated_residual.segment<2>(6)) / chord;
  // A tread ring turned by phi about a fixed rim stretches each pre-tensioned cord (rim
  // radius r, cord L, ring radius R) by R r phi^2 / (2 L): its pre-tension resists with
  // F r / (R L) = F/L - F/R per unit (R phi)^2, less than the F/L a tangential shift of a
  // single wedge shows. So the ring's rotational foundation stiffness is k_t - F/R.
  const double radius = 0.5 * (xa + xb).norm();
  const double mass = parameters.tread.mass_per_length;
  const double rotation_hz = std::sqrt((tangential_stiffness - pull / radius) / mass) / (2 * kPi);
  const double translation_hz = std::sqrt((radial_stiffness + tangential_stiffness) / (2 * mass)) / (2 * kPi);

  const ModalResult modes = modal_analysis(*inflated.analysis, 8);
  // Reference shapes: rigid rotation and x translation of the tread ring.
  Eigen::VectorXd rotation = Eigen::VectorXd::Zero(model.mesh().dof_count()), translation = rotation;
  for (int node : inflated.tire.tread_nodes) {
    const Eigen::Vector2d x = model.mesh().position(node);
    rotation.segment<3>(dof_index(node, 0)) << -x.y(), x.x(), 1.0;
    translation[dof_index(node, kUx)] = 1.0;
  }
  int rotation_mode = 0, translation_mode = 0;
  for (int m = 0; m < static_cast<int>(modes.frequencies_hz.size()); ++m) {
    if (mac(modes.shapes.col(m), rotation) > mac(modes.shapes.col(rotation_mode), rotation)) rotation_mode = m;
    // The translation pair may come in any orientation: x and y correlations together.
    Eigen::VectorXd turned = Eigen::VectorXd::Zero(translation.size());
    for (int node : inflated.tire.tread_nodes) turned[dof_index(node, kUy)] = 1.0;
    const auto pair_mac = [&](int k) {
      return mac(modes.shapes.col(k), translation) + mac(modes.shapes.col(k), turned);
    };
    if (pair_mac(m) > pair_mac(translation_mode)) translation_mode = m;
  }
  CHECK(pull > 0.5 * parameters.pressure * parameters.tread_width);  // most of p w goes into the sidewalls
  INFO("k_r = " << radial_stiffness << " N/m^2, k_t = " << tangential_stiffness << " N/m^2, F = " << pull
                << " N/m; modes:"
                << " rotation " << modes.frequencies_hz[rotation_mode] << " Hz (ring " << rotation_hz << "),"
                << " translation " << modes.frequencies_hz[translation_mode] << " Hz (ring " << translation_hz << ")");
  CHECK(mac(modes.shapes.col(rotation_mode), rotation) > 0.95);
  CHECK(modes.frequencies_hz[rotation_mode] == Approx(rotation_hz).epsilon(0.005));
  CHECK(modes.frequencies_hz[translation_mode] == Approx(translation_hz).epsilon(0.005));
  WARN("hub-fixed inflated 145 SR-12: n = 0 at " << modes.frequencies_hz[rotation_mode] << " Hz, n = 1 at "
                                                 << modes.frequencies_hz[translation_mode] << " Hz");
}

TEST_CASE("a lone tire, the paper's or the calibrated one, is solved by the RingSolver to KLU's answer",
          "[tire][solver]") {
  // prefer_ring_solver() picks the structured solver where the pattern fits: a ring of
  // belt nodes and its spindle; both tires inflate to the state a KLU-only analysis reaches.
  for (const char* set : {"tires.145SR12", "tires.145SR12_tread_layer"}) {
    INFO(set);
    const TireParameters parameters = macros::load_tire_parameters(set);
    Eigen::VectorXd displacement[2];
    bool ring_used[2] = {false, false};
    for (int preferred = 0; preferred < 2; ++preferred) {
      Model model;
      const Tire tire = build_tire(model, parameters, LoadFunction::linear());
      model.condense_node(tire.spindle);
      for (int c = 0; c < kDofsPerNode; ++c) model.fix(tire.spindle, c);
      Analysis analysis(model);
      if (preferred) analysis.prefer_ring_solver(tire.tread_nodes, {tire.spindle});
      analysis.set_time_step(0.25);
      analysis.advance(1.0);
      displacement[preferred] = analysis.state().displacement;
      ring_used[preferred] = analysis.ring_solver() != nullptr;
    }
    CHECK(!ring_used[0]);
    CHECK(ring_used[1]);
    CHECK((displacement[1] - displacement[0]).lpNorm<Eigen::Infinity>() <=
          1e-10 * displacement[0].lpNorm<Eigen::Infinity>());
  }
}
