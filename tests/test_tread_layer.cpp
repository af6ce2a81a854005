// TreadLayer: tangent against finite differences, rigid-body invariance, the spring
// law in the belt's rotating frame, and the batch path against evaluate().
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "core/model.hpp"
#include "elements/tread_layer.hpp"
#include "solvers/modal.hpp"
#include "test_support.hpp"

using namespace tirefe;

namespace {
TreadLayerProperties test_layer() {
  TreadLayerProperties layer;
  layer.radial_stiffness = 1.2e6;
  layer.circumferential_stiffness = 2.5e5;
  layer.mass = 4e-3;
  return layer;
}
}  // namespace

/// Compares the layer's tangent with central differences at 20 random large-deformation
/// dynamic states; 'symmetric': also checks that the tangent is symmetric.
static void check_tangent(const TreadLayer& layer, unsigned seed, bool symmetric) {
  std::mt19937 random(seed);
  for (int trial = 0; trial < 20; ++trial) {
    const auto local = testing::random_local_state<6>(random, 0.02, 2.0);
    double asymmetry = 0.0;
    INFO("trial " << trial);
    CHECK(testing::relative_tangent_error(layer, local, testing::dynamic_context(1e-3), &asymmetry) <= 1e-6);
    if (symmetric) CHECK(asymmetry <= 1e-12);
    CHECK(testing::declared_zero_magnitude(layer, local, testing::dynamic_context(1e-3)) == 0.0);
    CHECK(testing::mass_times_deviation(layer, local) <= 1e-15);
  }
}

TEST_CASE("tread layer tangent equals central finite differences of the residual", "[tread_layer]") {
  check_tangent(TreadLayer({0.2, 0.25}, test_layer()), 7, true);
}

TEST_CASE("damped tread layer: tangent equals finite differences; a strained layer turning rigidly is not damped",
          "[tread_layer]") {
  TreadLayerProperties properties = test_layer();
  properties.radial_damping = 40.0;
  properties.circumferential_damping = 9.0;
  const TreadLayer layer({0.2, 0.25}, properties);
  check_tangent(layer, 11, false);
  // A layer strained by d, turning with the belt at 50 rad/s (d' = theta' J d): no damping force.
  LocalState<6> local;
  local.displacement.setZero();
  local.velocity.setZero();
  local.acceleration.setZero();
  const double theta = 0.7, spin = 50.0;
  const Eigen::Vector2d strain = Eigen::Rotation2Dd(theta) * Eigen::Vector2d(1e-3, -4e-4);
  local.displacement.segment<2>(0) = strain;
  local.displacement[5] = theta;
  local.velocity.segment<2>(0) = spin * Eigen::Vector2d(-strain.y(), strain.x());
  local.velocity[5] = spin;
  EvaluationContext context = testing::dynamic_context(1e-3);
  context.factors.force_mass = 0.0;
  TreadLayer::Vector damped, undamped;
  NoHistory history;
  layer.evaluate(local, context, history, history, damped, nullptr);
  TreadLayer(Eigen::Vector2d(0.2, 0.25), test_layer()).evaluate(local, context, history, history, undamped, nullptr);
  CHECK((damped - undamped).norm() <= 1e-12 * undamped.norm());
  // Stretching at 0.1 m/s along the radial direction: the radial dashpot's force.
  local.velocity.setZero();
  local.displacement.setZero();
  const Eigen::Vector2d radial = Eigen::Vector2d(0.2, 0.25).normalized();
  local.velocity.segment<2>(0) = 0.1 * radial;
  layer.evaluate(local, context, history, history, damped, nullptr);
  CHECK(damped.segment<2>(0).dot(radial) == Approx(context.factors.force_damping * 40.0 * 0.1).epsilon(1e-12));
}

TEST_CASE("tread layer carries no force under a large rigid-body motion and balances moments", "[tread_layer]") {
  const Eigen::Vector2d node(0.21, -0.17);
  const TreadLayer layer(node, test_layer());
  NoHistory history;
  TreadLayer::Vector residual;
  for (double angle : {0.4, 2.2, -3.0}) {
    const Eigen::Rotation2Dd rotation(angle);
    const Eigen::Vector2d shift(0.3, -0.2), moved = rotation * node + shift - node;
    LocalState<6> local;
    local.velocity.setZero();
    local.acceleration.setZero();
    local.displacement << moved, 0.0, moved, angle;
    layer.evaluate(local, testing::dynamic_context(), history, history, residual, nullptr);
    CHECK(residual.norm() <= 1e-9);

    // Strained after the rigid motion: forces and moments about the origin balance.
    local.displacement.head<2>() += Eigen::Vector2d(0.004, -0.003);
    EvaluationContext statics;
    layer.evaluate(local, statics, history, history, residual, nullptr);
    const Eigen::Vector2d x_c = node + local.displacement.head<2>(), x_b = node + local.displacement.segment<2>(3);
    auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
    CHECK((residual.head<2>() + residual.segment<2>(3)).norm() <= 1e-9);
    CHECK(std::abs(cross(x_c, residual.head<2>()) + cross(x_b, residual.segment<2>(3)) + residual[5]) <= 1e-9);
  }
}

TEST_CASE("tread layer: radial and circumferential stiffness in the turned belt frame", "[tread_layer]") {
  const TreadLayerProperties properties = test_layer();
  const TreadLayer layer({0.0, 0.27}, properties);  // top of the tire: radial = +y, circumferential = -x
  NoHistory history;
  TreadLayer::Vector residual;
  EvaluationContext statics;
  LocalState<6> local;
  local.velocity.setZero();
  local.acceleration.setZero();

  local.displacement << 0.0, 1e-3, 0, 0, 0, 0;  // contact node 1 mm radially outward
  layer.evaluate(local, statics, history, history, residual, nullptr);
  CHECK(residual[1] == Approx(properties.radial_stiffness * 1e-3).epsilon(1e-12));
  CHECK(std::abs(residual[0]) <= 1e-12);

  // The belt section turned by 90 degrees: the same shift is now circumferential.
  local.displacement << 0.0, 1e-3, 0, 0, 0, 0.5 * M_PI;
  layer.evaluate(local, statics, history, history, residual, nullptr);
  CHECK(residual[1] == Approx(properties.circumferential_stiffness * 1e-3).epsilon(1e-12));
  CHECK(std::abs(residual[0]) <= 1e-9);
  CHECK(residual[4] == Approx(-residual[1]).epsilon(1e-12));

  // Inertia of the rubber on the contact node only.
  local.displacement.setZero();
  local.acceleration << 2.0, -3.0, 5.0, 7.0, 11.0, 13.0;
  statics.factors = {0.0, 0.0, 1.0, 0.0, 0.0, 1.0};
  TreadLayer::Matrix tangent;
  layer.evaluate(local, statics, history, history, residual, &tangent);
  CHECK(residual[0] == Approx(properties.mass * 2.0).epsilon(1e-12));
  CHECK(residual[1] == Approx(properties.mass * -3.0).epsilon(1e-12));
  CHECK(residual.tail<4>().norm() == 0.0);
  CHECK(tangent.trace() == Approx(2.0 * properties.mass).epsilon(1e-12));
}

TEST_CASE("contact node on a held belt node: two modes sqrt(k/m) and their support reactions -k phi",
          "[tread_layer][modal]") {
  // The belt node held, the contact node free (its rotation held): the radial and the
  // circumferential oscillation of the rubber mass, omega^2 = k/m, and the force each
  // mass-normalised shape (amplitude 1/sqrt(m)) puts on the held node, -k/sqrt(m) along it.
  const TreadLayerProperties properties = test_layer();
  Model model;
  const Eigen::Vector2d position(0.0, 0.27);  // radial = +y, circumferential along x
  const int contact = model.mesh().add_node(position);
  const int belt = model.mesh().add_node(position);
  model.add_block<TreadLayer>("layer").add({contact, belt}, TreadLayer(position, properties));
  for (int component : {0, 1, 2}) model.fix(belt, component);
  model.fix(contact, 2);
  const ModalResult modes = modal_analysis(model, State{}, 2);
  const double two_pi = 2.0 * M_PI, amplitude = 1.0 / std::sqrt(properties.mass);
  CHECK(modes.frequencies_hz[0] ==
        Approx(std::sqrt(properties.circumferential_stiffness / properties.mass) / two_pi).epsilon(1e-10));
  CHECK(modes.frequencies_hz[1] ==
        Approx(std::sqrt(properties.radial_stiffness / properties.mass) / two_pi).epsilon(1e-10));
  CHECK(std::abs(modes.shapes(dof_index(contact, 0), 0)) == Approx(amplitude).epsilon(1e-10));
  CHECK(modes.reactions(dof_index(belt, 0), 0) ==
        Approx(-properties.circumferential_stiffness * modes.shapes(dof_index(contact, 0), 0)).epsilon(1e-8));
  CHECK(std::abs(modes.reactions(dof_index(belt, 1), 0)) <= 1e-6 * properties.circumferential_stiffness * amplitude);
  CHECK(modes.reactions(dof_index(belt, 1), 1) ==
        Approx(-properties.radial_stiffness * modes.shapes(dof_index(contact, 1), 1)).epsilon(1e-8));
  CHECK(modes.reactions.col(0).segment<3>(dof_index(contact, 0)).head<2>().norm() == 0.0);  // free DOFs: none
}

TEST_CASE("tread layer batch path: every layer of a rolled ring as evaluate() gives it, to 1e-14", "[tread_layer]") {
  // 100 layers round a circle, two in three damped, strained by millimetres, the belt
  // nodes turned by hundreds of radians and spinning, static, Newmark and HHT.
  std::mt19937 random(13);
  constexpr int kLayers = 100;
  std::vector<TreadLayer> layers;
  std::vector<LocalState<6>> locals;
  for (int e = 0; e < kLayers; ++e) {
    TreadLayerProperties properties = test_layer();
    if (e % 3 != 0) {
      properties.radial_damping = 40.0 + e;
      properties.circumferential_damping = 9.0;
    }
    const double angle = 0.0628 * e;
    layers.emplace_back(Eigen::Vector2d(std::cos(angle), std::sin(angle)), properties);
    LocalState<6> local = testing::random_local_state<6>(random, 0.002, 0.05);
    local.displacement[5] += 3.1 * e - 100.0;
    local.velocity[5] *= 60.0;
    locals.push_back(local);
  }
  for (const EvaluationContext& context : testing::batch_contexts())
    for (bool with_tangent : {true, false}) {
      INFO("tangent " << with_tangent << ", mass factor " << context.factors.tangent_mass);
      CHECK(testing::batch_deviation(layers, locals, context, with_tangent) <= 1e-14);
    }
  // An undamped block takes the spring-only path.
  std::vector<TreadLayer> undamped(kLayers, TreadLayer({0.6, 0.8}, test_layer()));
  for (const EvaluationContext& context : testing::batch_contexts())
    CHECK(testing::batch_deviation(undamped, locals, context, true) <= 1e-14);
  // The stored energy the energy balance books each step, summed over the block.
  CHECK(testing::batch_energy_deviation(layers, locals) <= 1e-14);
}
