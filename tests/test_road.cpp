// The inflated 145 SR-12 on a road: a clear failure for a tread node jammed against a
// cleat wall.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "contact/node_contact.hpp"
#include "macros/macro_table.hpp"
#include "solvers/analysis.hpp"
#include "tire/tire_builder.hpp"

using namespace tirefe;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTolerance = 5e-4;  // the contact's penetration tolerance [m]

/// One accepted step of a loading run.
struct LoadPoint {
  double deflection = 0.0;     // spindle travel since first touch [m]
  double load = 0.0;           // vertical spindle force, upwards on the road [N]
  ContactSummary contact;
  int newton_iterations = 0;
  int cuts = 0;
  std::vector<std::pair<double, double>> forces;  // per tread node: x - x_spindle [m], t_N [N]
};

/// The 145 SR-12 inflated to 208 kPa on a held hub (t in [0, 1]); a surface touching its
/// lowest tread node is added with contact() and the spindle pressed down by press().
struct TireOnRoad {
  Model model;
  Tire tire;
  std::unique_ptr<Analysis> analysis;
  ContactBlock* contact = nullptr;
  int press_function = -1;
  double lowest = 0.0;          // y of the lowest tread point after inflation [m]
  double inflated_radius = 0.0;

  explicit TireOnRoad(int elements = 100) {
    TireParameters parameters = macros::load_tire_parameters("tires.145SR12");
    parameters.elements = elements;
    tire = build_tire(model, parameters, LoadFunction::table({{0.0, 0.0}, {1.0, 1.0}}));
    for (int c = 0; c < kDofsPerNode; ++c) model.fix(tire.spindle, c);
    press_function = model.add_load_function(LoadFunction::table({{1.0, 0.0}, {2.0, 1.0}}));
    analysis = std::make_unique<Analysis>(model);
    analysis->set_time_step(0.25);
    analysis->advance(1.0);
    lowest = 1e9;
    for (int node : tire.tread_nodes) lowest = std::min(lowest, position(node).y());
    inflated_radius = -lowest;
  }

  Eigen::Vector2d position(int node) const {
    return model.mesh().position(node) + analysis->state().displacement.segment<2>(dof_index(node, 0));
  }

  /// Contact with penalties scaled from the inflated tire (docs/contact.md).
  void add_contact(std::shared_ptr<const RigidSurface> surface, double friction) {
    ContactParameters parameters;
    parameters.friction = friction;
    parameters.normal_penalty = structural_penalty(*analysis, tire.tread_nodes);
    parameters.tangential_penalty = structural_tangential_penalty(*analysis, tire.tread_nodes, *surface);
    contact = &add_contact_block(model, "contact", std::move(surface), tire.tread_nodes, parameters,
                                 analysis->state().time);
  }

  /// Presses the spindle down to 'deepest' in 'steps' quasi-static steps (t from 1 to 2).
  std::vector<LoadPoint> press(double deepest, int steps) {
    model.prescribe(tire.spindle, kUy, -deepest, press_function);
    std::vector<LoadPoint> points;
    analysis->set_time_step(1.0 / steps);
    for (int i = 1; i <= steps; ++i) {
      const StepRecord record = analysis->advance().back();
      points.push_back(load_point(record));
    }
    return points;
  }

  LoadPoint load_point(const StepRecord& record) const {
    LoadPoint point;
    point.deflection = -analysis->state().displacement[dof_index(tire.spindle, kUy)];
    point.load = -analysis->reactions()[dof_index(tire.spindle, kUy)];
    point.contact = summarize_contact(*contact);
    point.newton_iterations = record.newton_iterations;
    point.cuts = record.cuts;
    point.forces = contact_forces();
    return point;
  }

  /// Horizontal offset of each tread node from the spindle and its normal force.
  std::vector<std::pair<double, double>> contact_forces() const {
    std::vector<std::pair<double, double>> forces;
    const double spindle_x = position(tire.spindle).x();
    for (int i = 0; i < contact->size(); ++i)
      forces.emplace_back(position(tire.tread_nodes[i]).x() - spindle_x, contact->committed_history(i).normal_force);
    return forces;
  }
};


}  // namespace

TEST_CASE("a tread node jammed against a vertical cleat wall ends the run with a StepFailure", "[road][contact][failure]") {
  // The spindle is held and the road frictionless: a pressed tread node cannot climb a
  // vertical wall quasi-statically. Steps that scrape through at tiny sizes must not let the
  // step dwindle without end: the run stops below the nominal step / 4^max_cuts.
  TireOnRoad tire;
  tire.add_contact(std::make_shared<RoadProfile>(RoadProfile::cleat_points(0.15, 0.2, 0.01, tire.lowest), 0.0,
                                                 RigidMotion::translation(MotionFunction::ramped_rate(-0.5, 0.0, 2.0))),
                   0.0);
  tire.press(0.020, 10);
  tire.analysis->step_control().max_cuts = 6;
  tire.analysis->set_time_step(0.004);
  int accepted = 0;
  double smallest = 1.0;
  tire.analysis->add_step_observer([&](const Analysis&, const StepRecord& record) {
    ++accepted;
    smallest = std::min(smallest, record.step_size);
  });
  CHECK_THROWS_AS(tire.analysis->advance(1.0), StepFailure);
  CHECK(smallest >= 0.004 / 4096 * (1.0 - 1e-9));
  CHECK(accepted < 1000);
  CHECK(tire.analysis->state().displacement.allFinite());
}
