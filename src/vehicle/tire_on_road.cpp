#include "vehicle/tire_on_road.hpp"

#include <cstdio>
#include <limits>
#include <string>

#include "tire/contact_penalty.hpp"

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
  // The ring of tread nodes and the spindle; a tread layer's contact nodes are satellites
  // of their belt nodes, and the road (a rigid surface) couples each to itself only.
  analysis_->use_ring_solver(tire_.tread_nodes, {tire_.spindle});
  analysis_->set_time_step(0.25);
  try {
    analysis_->advance(1.0);
  } catch (const StepFailure&) {  // no step size of the host's would help: the parameters are at fault
    throw ModelError("the tire cannot be inflated on its hub with these parameters (" + analysis_->last_failure() +
                     "); check the pressure and the stiffnesses");
  }

  // The nodes that touch the road are the tire's contact nodes (the tread layer's, or the
  // tread's without one), as for model:tire in a deck and lua/tire_on_road.lua.
  const std::vector<int>& touching = tire_.contact_nodes;
  road_level_ = std::numeric_limits<double>::infinity();
  for (int node : touching)
    road_level_ =
        std::min(road_level_, model_.mesh().position(node).y() + analysis_->state().displacement[dof_index(node, 1)]);
  const std::shared_ptr<const RigidSurface> surface = road(road_level_);
  ContactParameters penalties;
  penalties.friction = contact.friction;
  penalties.normal_penalty = structural_penalty(*analysis_, touching, contact.penalty_factor);
  penalties.tangential_penalty =
      structural_tangential_penalty(*analysis_, touching, *surface, contact.tangential_factor);
  contact_ = &add_contact_block(model_, "contact", surface, touching, penalties, analysis_->state().time);
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
  return *spindle_;
}

}  // namespace tirefe
