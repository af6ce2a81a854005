// Queries between steps (support reactions, an initial acceleration, a contact penalty's
// scale, modal matrices and force probes) evaluate the elements through
// Assembler::query, which puts the trial history back to the committed one: a query
// leaves no trace in the elements, and the steps that follow are those of a run that made
// none, bit for bit.
#include <catch2/catch.hpp>

#include <cstring>
#include <memory>

#include "contact/rigid_surface.hpp"
#include "macros/macro_table.hpp"
#include "solvers/modal.hpp"
#include "tire/contact_penalty.hpp"
#include "vehicle/tire_on_road.hpp"

using namespace tirefe;

namespace {

/// The 145 SR-12 tire pressed 15 mm onto a still flat road with friction (mu = 0.8).
std::unique_ptr<TireOnRoad> pressed_tire() {
  auto tire = std::make_unique<TireOnRoad>(
      macros::load_tire_parameters("tires.145SR12"),
      [](double level) { return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, level)); }, RoadContact{0.8});
  tire->press(0.015);
  return tire;
}

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

/// Every contact element's trial history is its committed one, byte for byte.
bool history_as_committed(const TreadContactBlock& contact) {
  for (int e = 0; e < contact.size(); ++e)
    if (std::memcmp(static_cast<const void*>(&contact.trial_history(e)),
                    static_cast<const void*>(&contact.committed_history(e)), sizeof(contact.trial_history(e))) != 0)
      return false;
  return true;
}

}  // namespace

TEST_CASE("queries between steps leave the elements' history and the next steps alone, bit for bit",
          "[kernel][history]") {
  const auto quiet = pressed_tire();
  const auto queried = pressed_tire();
  Analysis& analysis = queried->analysis();
  const std::vector<int>& nodes = queried->tire().tread_nodes;
  REQUIRE(same_bits(quiet->analysis().state().displacement, analysis.state().displacement));

  // Queries at the committed state and, for the modal analysis, at a state 2 mm deeper in
  // the road, where the contact's trial history would differ from the committed one.
  CHECK(structural_penalty(analysis, nodes, 1.0) > 0.0);
  CHECK(history_as_committed(queried->contact()));
  State deeper = analysis.state();
  for (int node : nodes) deeper.displacement[dof_index(node, kUy)] -= 0.002;
  CHECK(modal_analysis(queried->model(), deeper, 3).frequencies_hz.size() == 3);
  CHECK(history_as_committed(queried->contact()));

  for (TireOnRoad* tire : {quiet.get(), queried.get()}) tire->analysis().set_integrator(Integrator::hht(-0.1));
  analysis.initialize_acceleration();  // the quiet run does it at its first step
  CHECK(history_as_committed(queried->contact()));
  CHECK(structural_penalty(analysis, nodes, 1.0) > 0.0);

  for (TireOnRoad* tire : {quiet.get(), queried.get()}) {
    tire->analysis().set_time_step(1e-4);
    tire->analysis().advance(5e-4);
  }
  const State& expected = quiet->analysis().state();
  const State& got = analysis.state();
  CHECK(got.time == expected.time);
  CHECK(same_bits(got.displacement, expected.displacement));
  CHECK(same_bits(got.velocity, expected.velocity));
  CHECK(same_bits(got.acceleration, expected.acceleration));
  CHECK(same_bits(analysis.reactions(), quiet->analysis().reactions()));
  CHECK(quiet->contact().committed_history_bytes() == queried->contact().committed_history_bytes());
}
