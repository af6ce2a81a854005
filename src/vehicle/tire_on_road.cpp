#include "vehicle/tire_on_road.hpp"

#include <cstdio>
#include <limits>
#include <string>

#include "tire/wheel_axes.hpp"

namespace tirefe {

TireOnRoad::TireOnRoad(const TireParameters& parameters, const RoadMaker& road, const RoadContact& contact) {
  // Without pressure the tire is slack where it meets the road, and its contact stiffness,
  // scaled from the structure there, cannot be set.
  if (!(parameters.pressure > 0.0)) {
    char text[128];
    std::snprintf(text, sizeof text,
                  "parameter 'pressure' is %g Pa: a tire on the road is inflated before it touches it",
                  parameters.pressure);
    throw ModelError(std::string(text) + "; give a pressure > 0");
  }
  TireParameters centred = parameters;
  centred.centre.setZero();
  tire_ = build_tire(model_, centred, LoadFunction::table({{0.0, 0.0}, {1.0, 1.0}}));
  model_.condense_node(tire_.spindle);
  for (int c = 0; c < kDofsPerNode; ++c) model_.fix(tire_.spindle, c);
  analysis_ = std::make_unique<Analysis>(model_);
  // The ring of tread nodes and the spindle; the tread contact couples a chord's two nodes,
  // as the tread beam does.
  analysis_->use_ring_solver(tire_.tread_nodes, {tire_.spindle});
  analysis_->set_time_step(0.25);
  try {
    analysis_->advance(1.0);
  } catch (const StepFailure&) {  // no step size of the host's would help: the parameters are at fault
    throw ModelError("the tire cannot be inflated on its hub with these parameters (" + analysis_->last_failure() +
                     "); check the pressure and the stiffnesses");
  }

  // The road touches the lowest tread node.
  road_level_ = std::numeric_limits<double>::infinity();
  for (int node : tire_.tread_nodes)
    road_level_ =
        std::min(road_level_, model_.mesh().position(node).y() + analysis_->state().displacement[dof_index(node, 1)]);
  contact_ = &add_tread_contact_block(model_, "contact", road(road_level_), tire_.tread_nodes,
                                      tread_rubber(tire_.parameters, contact.friction));
}

double TireOnRoad::press(double deflection) {
  if (spindle_) throw ModelError("the tire is driven by its spindle already: press it before drive()");
  const double time = analysis_->state().time;
  const double now = analysis_->state().displacement[dof_index(tire_.spindle, 1)];
  model_.prescribe(tire_.spindle, 1, 1.0,
                   model_.add_load_function(LoadFunction::table({{time, now}, {time + 1.0, -deflection}})));
  analysis_->advance(1.0);
  return analysis_->reactions()[dof_index(tire_.spindle, 1)];
}

TireSpindle& TireOnRoad::drive(const Integrator& integrator, SpinMode spin) {
  analysis_->set_integrator(integrator);
  spindle_ = std::make_unique<TireSpindle>(*analysis_, tire_.spindle, spin);
  // The host takes the spindle over at rest and holds it there: the tire starts with the
  // accelerations of its equilibrium and the spindle's zero, not those of a rim let go
  // under its load (which the first held steps would turn into a ringing of the force).
  analysis_->initialize_acceleration();
  for (int c = 0; c < (spin == SpinMode::Free ? 2 : kDofsPerNode); ++c)
    analysis_->mutable_state().acceleration[dof_index(tire_.spindle, c)] = 0.0;
  return *spindle_;
}

std::vector<double> static_vertical_forces(const TireParameters& parameters, const std::vector<double>& deflections,
                                           const std::function<void()>& between_presses) {
  TireOnRoad tire(
      parameters, [](double level) { return std::make_shared<FlatRoad>(Eigen::Vector2d(0.0, level)); },
      RoadContact{0.0});
  std::vector<double> forces;
  forces.reserve(deflections.size());
  for (double deflection : deflections) {
    if (between_presses) between_presses();
    const double reaction_y = tire.press(deflection);
    forces.push_back(wheel_load_from_reaction(Eigen::Vector3d(0.0, reaction_y, 0.0), Heading::PlusX).y());
  }
  return forces;
}

}  // namespace tirefe
